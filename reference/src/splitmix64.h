// The reference side's one pseudo-random stream (light samples, hair), the
// same on every platform: no std:: distributions, whose output differs
// between standard libraries. Private to reference/src.
#pragma once

#include <cstdint>

namespace penumbra::reference {

// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit counter pushed through a
// bijective mixer. Cheap, stateless to seed, and good enough for jitter.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t state) : state_(state) {}

    std::uint64_t next()
    {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1): the top 53 bits as a double's mantissa.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
    std::uint64_t state_;
};

}  // namespace penumbra::reference
