// The interface every backend implements (simd/cpu_backend.h,
// cl/opencl_backend.h): one method per host operation; host/src/*.cpp call it.
// Inputs are validated before these are called; a backend trusts its
// arguments. The kernels it runs are named by KernelId (kernel_id.h, beside
// this file).
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
    // Cross-bilateral filter (kernels/bilateral.h) of `mask` into `out`.
    // `normals` is null unless params.use_normals; `taps` holds the window's
    // offsets as (dx, dy) pairs (separable: (d, d)), `weights` their spatial
    // weights and base-2 exponents as pairs; `params` is complete but for
    // `pass` and `pass_first_row`, which the separable schedule sets.
    // bad_rows: per mask row.
    virtual void cross_bilateral(const Image& mask, const Image& guide, const Image* normals,
                                 const std::vector<int>& taps, const std::vector<float>& weights, bool separable,
                                 const BilateralParams& params, Image& out, int* bad_rows) = 0;
    // SDF soft shadows (kernels/sdf.h) through a distance grid (`data`: the
    // nodes) or analytic primitives (`data`: the packed records, `floats` of
    // them, possibly none). `normals` is `positions` when params.normal_offset
    // is 0; `out` has 1 or 2 planes; `params` is complete; bad_rows: per receiver row.
    virtual void sdf_grid(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                          const SdfParams& params, Image& out, int* bad_rows) = 0;
    virtual void sdf_analytic(const float* data, std::size_t floats, const Image& positions, const Image& normals,
                              const SdfParams& params, Image& out, int* bad_rows) = 0;
    // The moment family (kernels/encoded_table.h, msm.h, msm_soft.h, evsm.h).
    // Fills `table` (zeroed, params.channels planes) with the sums of encoded
    // texels; `params` is complete but for columns and band_height, which the
    // schedule sets. bad_rows: per depth row.
    virtual void build_encoded_table(const Image& depth, const EncodedSatParams& params, MomentTable& table,
                                     int* bad_rows) = 0;
    enum class MomentMethod { Msm, MsmSoft, Evsm };
    // `params` is complete; bad_rows: per receiver row.
    virtual void moment_lookup(MomentMethod method, const MomentTable& table, const Image& receivers,
                               const MomentParams& params, Image& out, int* bad_rows) = 0;
};

pn_dims dims_of(const Image& image);
pn_dims dims_of(const MomentTable& table);

// The moment table build's parameters for `depth` into `table`, with
// `column_rows` rows of column totals and bands of `band_height` rows (the
// schedule's choice): both backends' builds start from these.
SatParams sat_params(const Image& depth, const MomentTable& table, int column_rows, int band_height);
// The join pass of a banded encoded build (kernels/moment_table.h's
// sat_join_bands_*) reads the encoded table as a one-limb moment table.
SatParams join_params(const EncodedSatParams& p);

}  // namespace penumbra::detail
