// One light ray's transmittance function of depth (Lokovic and Veach 2000,
// "The Transmittance Function"): the surface transmittance, a step of
// 1 - opacity at each hit, times the volume transmittance, from extinction
// sampled at regular steps and linearly interpolated, T evaluated at the
// samples. Both are merged in one sweep over the ray's events, so every
// vertex of either is a vertex of the result and T is evaluated there
// (not interpolated across a surface inside fog).
#include <algorithm>
#include <cmath>

#include "penumbra/reference/deep_map.h"

namespace penumbra::reference {
namespace {

// The sweep's state: the surface product, the optical depth so far, the media
// the ray is inside, and the vertices written.
class Sweep {
public:
    // Steps per span at most: where the rule asks for more (a medium of
    // extinction ~10^5 per unit over metres), the volume error is not met.
    static constexpr int kMaxSteps = 1 << 16;

    Sweep(const PreparedScene& prepared, const LightProjection& projection, const Ray& ray, double volume_error)
        : prepared_(prepared), projection_(projection), ray_(ray), volume_error_(volume_error)
    {
    }

    // The media's k at depth parameter t: the linear functions of the open
    // media (extinction_within: a point on a boundary counts as inside).
    double extinction(double t) const
    {
        double k = 0;
        for (int m : open_) k += prepared_.media()[std::size_t(m)].extinction_within(ray_.at(t));
        return k;
    }

    // Advances from the last event to t through the open media, writing a
    // vertex at each regular sample (the rule of ray_transmittance, deep_map.h).
    void march_to(double t)
    {
        if (open_.empty() || !(t > t_)) {
            t_ = std::max(t_, t);
            return;
        }
        const double scale = length(ray_.direction);  // world length per unit of t
        const double k0 = extinction(t_), k1 = extinction(t);
        const double span = scale * (t - t_);
        const double bound = std::max(k0, k1) * std::max(k0, k1) + std::abs(k1 - k0) / span;
        const double step = std::sqrt(8 * volume_error_ / bound);
        // In double first: a dense medium over a long span would overflow an int.
        const int steps = int(std::clamp(std::ceil(span / step), 1.0, double(kMaxSteps)));
        const double t_start = t_;
        double k_prev = k0;
        for (int i = 1; i <= steps; ++i) {
            // Once T is within volume_error of 0, a chord to the span's end is
            // too (T stays between its end values), so the rest is one step.
            const bool last = i == steps || value() <= volume_error_;
            const double ti = last ? t : t_start + (t - t_start) * i / steps;
            const double ki = last ? k1 : extinction(ti);
            tau_ += 0.5 * (k_prev + ki) * scale * (ti - t_);  // trapezoid: exact for linear k
            t_ = ti;
            k_prev = ki;
            vertex(ti, value());
            if (last) break;
        }
    }

    void surface(double t, double opacity)
    {
        vertex(t, value());
        surviving_ *= 1 - opacity;
        vertex(t, value());
    }
    void enter(double t, int medium)
    {
        if (open_.empty()) vertex(t, value());  // where T starts to fall
        open_.push_back(medium);
    }
    void leave(int medium) { std::erase(open_, medium); }

    RayFunction take() { return std::move(out_); }

private:
    double value() const { return surviving_ == 0 ? 0 : surviving_ * std::exp(-tau_); }
    void vertex(double t, double value)
    {
        out_.z.push_back(float(projection_.z_of(t)));
        out_.t.push_back(value);
    }

    const PreparedScene& prepared_;
    const LightProjection& projection_;
    const Ray& ray_;
    double volume_error_;
    double t_ = -INFINITY, tau_ = 0, surviving_ = 1;
    std::vector<int> open_;
    RayFunction out_;
};

}  // namespace

RayFunction ray_transmittance(const PreparedScene& prepared, const LightProjection& projection, const Ray& ray,
                              double near, double far, double volume_error)
{
    Sweep sweep(prepared, projection, ray, volume_error);
    for (const RayEvent& e : prepared.events(ray, near, far)) {
        sweep.march_to(e.t);
        switch (e.kind) {
        case RayEvent::Kind::Surface: sweep.surface(e.t, e.opacity); break;
        case RayEvent::Kind::MediumEntry: sweep.enter(e.t, e.index); break;
        case RayEvent::Kind::MediumExit: sweep.leave(e.index); break;
        }
    }
    return sweep.take();
}

}  // namespace penumbra::reference
