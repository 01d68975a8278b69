// The interface every backend implements: one method per host operation.
// Inputs are validated before these are called (host/src/*.cpp); a backend
// trusts its arguments.
#pragma once

#include <string>

#include "kernels/params.h"
#include "penumbra/image.h"
#include "penumbra/moment_table.h"

namespace penumbra::detail {

enum class ChebyshevMethod { Vsm, Vssm };

class BackendImpl {
public:
    virtual ~BackendImpl() = default;
    virtual std::string description() const = 0;
    virtual std::string isa() const { return {}; }
    virtual double program_build_seconds() const { return 0.0; }

    // Kernels check the values they read: `bad_rows` (one int per row of the
    // input they check, zeroed) gets a 1 for every row holding a value the
    // kernel cannot take; the host then finds and reports the first one.

    // Fills `table` from `depth`; bad_rows: per depth row.
    virtual void build_moment_table(const Image& depth, MomentTable& table, int* bad_rows) = 0;
    // `params` is complete; bad_rows: per receiver row.
    virtual void chebyshev(ChebyshevMethod method, const MomentTable& table, const Image& receivers,
                           const ChebyshevParams& params, Image& out, int* bad_rows) = 0;
};

pn_dims dims_of(const Image& image);
pn_dims dims_of(const MomentTable& table);

}  // namespace penumbra::detail
