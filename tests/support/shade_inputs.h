// A CLI fixture with the inputs of a `penumbra shade` run in its folder:
// sm.exr (a 37 x 23 random depth map, channel Z) and rx.exr (29 x 17
// receivers on its texels, channels u v z; a grid that is not the map's, so
// that lookups land between texels). Kept as map_ and rx_ for the library's
// side of a comparison.
#pragma once

#include "penumbra/exr_io.h"
#include "penumbra/image.h"
#include "support/cli.h"
#include "support/maps.h"

namespace penumbra::testing {

class ShadeInputs : public CliFixture {
protected:
    void SetUp() override
    {
        CliFixture::SetUp();
        map_ = random_depth(37, 23, 4);
        rx_ = receivers_on_texels(29, 17, 37, 23, 0.2f, 0.9f, 8);
        write_exr(path("sm.exr"), map_, {"Z"});
        write_exr(path("rx.exr"), rx_, {"u", "v", "z"});
    }

    Image map_, rx_;
};

}  // namespace penumbra::testing
