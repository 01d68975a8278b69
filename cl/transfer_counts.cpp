#include "cl/transfer_counts.h"

#include <atomic>

#include "cl/opencl_launch.h"

namespace penumbra::cl_backend {
namespace {

// Relaxed: counts, read by a test or benchmark after the work they count.
std::atomic<long> uploads{0}, downloads{0};
std::atomic<std::size_t> upload_bytes{0}, download_bytes{0};

}  // namespace

void count_upload(std::size_t bytes)
{
    uploads.fetch_add(1, std::memory_order_relaxed);
    upload_bytes.fetch_add(bytes, std::memory_order_relaxed);
}

void count_download(std::size_t bytes)
{
    downloads.fetch_add(1, std::memory_order_relaxed);
    download_bytes.fetch_add(bytes, std::memory_order_relaxed);
}

HostTransfers transfer_counts()
{
    return {uploads.load(std::memory_order_relaxed), downloads.load(std::memory_order_relaxed),
            upload_bytes.load(std::memory_order_relaxed), download_bytes.load(std::memory_order_relaxed)};
}

}  // namespace penumbra::cl_backend
