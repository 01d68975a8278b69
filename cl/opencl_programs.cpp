#include "cl/opencl_programs.h"

#include <string>

namespace penumbra::cl_backend {

using detail::KernelFamily;
using detail::KernelId;

#define PN_FAMILY_SOURCE_DECLARATION(family) extern const char* const kProgramSource_##family;
PN_KERNEL_FAMILIES(PN_FAMILY_SOURCE_DECLARATION)
#undef PN_FAMILY_SOURCE_DECLARATION

const char* program_source(KernelFamily family)
{
    static const std::array<const char*, detail::kFamilyCount> sources{
#define PN_FAMILY_SOURCE(family) kProgramSource_##family,
        PN_KERNEL_FAMILIES(PN_FAMILY_SOURCE)
#undef PN_FAMILY_SOURCE
    };
    return sources[static_cast<int>(family)];
}

cl::Kernel& FamilyPrograms::kernel(KernelId id)
{
    build(detail::kernel_family(id));
    return kernels_[static_cast<int>(id)];  // written once, under the lock, before built_ was set
}

void FamilyPrograms::build(KernelFamily family)
{
    std::lock_guard lock(build_mutex_);
    build_locked(family);
}

void FamilyPrograms::build_all()
{
    std::lock_guard lock(build_mutex_);
    for (int f = 0; f < detail::kFamilyCount; ++f) build_locked(static_cast<KernelFamily>(f));
}

// Runtime::build() is not reentrant (it records its timing): the lock covers it.
void FamilyPrograms::build_locked(KernelFamily family)
{
    const int f = static_cast<int>(family);
    if (built_[f]) return;
    programs_[f] = runtime_.build(program_source(family), kProgramOptions);
    build_seconds_ += runtime_.last_build_seconds();
    translate_cl_errors([&] {
        for (int k = 0; k < detail::kKernelCount; ++k) {
            const auto id = static_cast<KernelId>(k);
            if (detail::kernel_family(id) == family)
                kernels_[k] = cl::Kernel(programs_[f], std::string(detail::kernel_name(id)).c_str());
        }
    });
    built_[f] = true;
}

bool FamilyPrograms::built(KernelFamily family) const
{
    std::lock_guard lock(build_mutex_);
    return built_[static_cast<int>(family)];
}

int FamilyPrograms::programs_built() const
{
    std::lock_guard lock(build_mutex_);
    int count = 0;
    for (bool b : built_) count += b ? 1 : 0;
    return count;
}

double FamilyPrograms::build_seconds() const
{
    std::lock_guard lock(build_mutex_);
    return build_seconds_;
}

}  // namespace penumbra::cl_backend
