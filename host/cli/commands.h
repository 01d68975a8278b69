// The subcommands of the `penumbra` tool. Each returns the process exit status;
// bad input throws penumbra::Error or cli::UsageError, which main() reports.
#pragma once

#include <string>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/reference/render.h"

namespace penumbra::cli {

int info_command(const std::vector<std::string>& args);
int shade_command(const std::vector<std::string>& args);
int example_command(const std::vector<std::string>& args);
int render_scene_command(const std::vector<std::string>& args);
int demo_command(const std::vector<std::string>& args);
int dsm_build_command(const std::vector<std::string>& args);
int pismo_build_command(const std::vector<std::string>& args);

// Shared by render-scene and demo.
struct ViewSize {
    int width = 0, height = 0;
};
// "WxH", each size in [1, largest]; a UsageError names `option`.
ViewSize parse_view_size(const std::string& text, const std::string& option = "--view-size", int largest = 16384);
int strata_for_samples(int samples);                // n such that n^2 ~ samples
// The receivers as one image with the channels of kReceiverChannels.
extern const std::vector<std::string> kReceiverChannels;
Image pack_receivers(const reference::Receivers& receivers);
int blur_command(const std::vector<std::string>& args);
int ambient_command(const std::vector<std::string>& args);
int mask_command(const std::vector<std::string>& args);

}  // namespace penumbra::cli
