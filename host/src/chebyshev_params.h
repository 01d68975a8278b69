// VSM's and VSSM's lookup parameters over a table, from geometry alone: shared by the
// Image form (chebyshev.cpp) and the device-resident one (device_image.cpp).
#pragma once

#include <string>

#include "kernels/params.h"
#include "penumbra/chebyshev.h"

namespace penumbra::detail {

// Checks the options (Error naming min_variance, bleed, radius) and fills the Params.
ChebyshevParams vsm_table_params(const std::string& op, pn_dims table, Precision precision, int limbs,
                                 pn_dims receivers, pn_dims out, const VsmOptions& options);
// Checks the options (min_variance, bleed, light-size against the table's search limit) and fills the Params.
ChebyshevParams vssm_table_params(const std::string& op, pn_dims table, Precision precision, int limbs,
                                  pn_dims receivers, pn_dims out, const VssmOptions& options);

}  // namespace penumbra::detail
