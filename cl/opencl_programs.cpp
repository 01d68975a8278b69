#include "cl/opencl_programs.h"

#include "cl/opencl_prime.h"

namespace penumbra::cl_backend {

using detail::KernelFamily;
using detail::KernelId;

#define PN_FAMILY_SOURCE_DECLARATION(family) extern const char* const kProgramSource_##family;
PN_KERNEL_FAMILIES(PN_FAMILY_SOURCE_DECLARATION)
#undef PN_FAMILY_SOURCE_DECLARATION

const char* family_source(KernelFamily family)
{
    static const std::array<const char*, detail::kFamilyCount> sources{
#define PN_FAMILY_SOURCE(family) kProgramSource_##family,
        PN_KERNEL_FAMILIES(PN_FAMILY_SOURCE)
#undef PN_FAMILY_SOURCE
    };
    return sources[static_cast<int>(family)];
}

// The one line that makes PN_ENTRY(name) a kernel (cl/dialect_cl.h); the
// family source's #line markers keep the build log's lines those of the files.
std::string program_source(KernelId id)
{
    return "#define PN_ENTRY_IS_" + std::string(detail::kernel_name(id)) + " ~, kernel\n" +
           family_source(detail::kernel_family(id));
}

cl::Kernel& KernelPrograms::kernel(KernelId id)
{
    std::lock_guard lock(build_mutex_);
    build_locked(id);
    return kernels_[static_cast<int>(id)];  // written once, under the lock, before built_ was set
}

void KernelPrograms::build_all()
{
    std::lock_guard lock(build_mutex_);
    for (int k = 0; k < detail::kKernelCount; ++k) build_locked(static_cast<KernelId>(k));
}

// Runtime::build() is not reentrant (it records its timing): the lock covers it.
void KernelPrograms::build_locked(KernelId id)
{
    const int k = static_cast<int>(id);
    if (built_[k]) return;
    // Launched once before its binary is stored, so that the binary holds the
    // work-group function of the fixed local size (cl/opencl_prime.h).
    const auto prime = [&](const cl::Program& built) {
        prime_kernel(runtime_.context(), runtime_.queue(), built, id, runtime_.work_groups());
    };
    const cl::Program program = runtime_.build(program_source(id), kProgramOptions, prime);
    build_seconds_ += runtime_.last_build_seconds();
    const std::string name(detail::kernel_name(id));
    kernels_[k] = translate_cl_errors([&] { return cl::Kernel(program, name.c_str()); });
    built_[k] = true;
}

bool KernelPrograms::built(KernelId id) const
{
    std::lock_guard lock(build_mutex_);
    return built_[static_cast<int>(id)];
}

int KernelPrograms::programs_built() const
{
    std::lock_guard lock(build_mutex_);
    int count = 0;
    for (bool b : built_) count += b ? 1 : 0;
    return count;
}

double KernelPrograms::build_seconds() const
{
    std::lock_guard lock(build_mutex_);
    return build_seconds_;
}

}  // namespace penumbra::cl_backend
