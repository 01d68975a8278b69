// The process's count of host <-> device transfers (cl/opencl_launch.h's
// count_upload / count_download add to it): penumbra::host_transfers().
#pragma once

#include "penumbra/device_image.h"

namespace penumbra::cl_backend {

HostTransfers transfer_counts();

}  // namespace penumbra::cl_backend
