#include "support/moment_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace penumbra::testing {
namespace {

using Vec = std::vector<double>;
using Mat = std::vector<Vec>;

// Solves a x = y by Gaussian elimination with partial pivoting.
Vec solve(Mat a, Vec y)
{
    const std::size_t n = y.size();
    for (std::size_t col = 0; col < n; ++col) {
        std::size_t pivot = col;
        for (std::size_t row = col + 1; row < n; ++row)
            if (std::abs(a[row][col]) > std::abs(a[pivot][col])) pivot = row;
        std::swap(a[col], a[pivot]);
        std::swap(y[col], y[pivot]);
        for (std::size_t row = col + 1; row < n; ++row) {
            const double f = a[row][col] / a[col][col];
            for (std::size_t k = col; k < n; ++k) a[row][k] -= f * a[col][k];
            y[row] -= f * y[col];
        }
    }
    Vec x(n);
    for (std::size_t i = n; i-- > 0;) {
        double s = y[i];
        for (std::size_t k = i + 1; k < n; ++k) s -= a[i][k] * x[k];
        x[i] = s / a[i][i];
    }
    return x;
}

// Weights of the atoms at `points` reproducing moments 0 .. points.size()-1.
std::vector<Atom> weights_at(const std::vector<double>& points, const Moments4& b)
{
    const std::size_t n = points.size();
    Mat v(n, Vec(n));
    Vec y(n);
    for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t i = 0; i < n; ++i) v[k][i] = std::pow(points[i], double(k));
        y[k] = b[k];
    }
    const Vec w = solve(v, y);
    std::vector<Atom> atoms;
    for (std::size_t i = 0; i < n; ++i) atoms.push_back({points[i], w[i]});
    return atoms;
}

double mass_below(const std::vector<Atom>& atoms, double z)
{
    double g = 0.0;
    for (const Atom& a : atoms)
        if (a.x < z) g += a.w;
    return g;
}

const std::array<std::array<double, 4>, 4> kT{{{-2.07224649, 32.23703778, -68.571074599, 39.3703274134},
                                               {13.7948857237, -59.4683975703, 82.0359750338, -35.364903257},
                                               {0.105877704, -1.9077466311, 9.3496555107, -6.6543490743},
                                               {9.7924062118, -33.7652110555, 47.9456096605, -23.9728048165}}};
const std::array<std::array<double, 4>, 4> kTInverse{{{0.2227744146, 0.0771972861, 0.7926986636, 0.0319417555},
                                                      {0.1549679261, 0.1394629426, 0.7963415838, -0.1722823173},
                                                      {0.1451988946, 0.2120202157, 0.7258694464, -0.2758014811},
                                                      {0.163127443, 0.2591432266, 0.6539092497, -0.3376131734}}};
constexpr double kOffset = 0.035955884801;

}  // namespace

Moments4 moments_of(const std::vector<Atom>& atoms)
{
    Moments4 b{};
    double total = 0.0;
    for (const Atom& a : atoms) total += a.w;
    for (const Atom& a : atoms)
        for (int k = 0; k <= 4; ++k) b[k] += a.w / total * std::pow(a.x, double(k));
    return b;
}

Moments4 biased(const Moments4& b, double alpha)
{
    Moments4 out = b;
    for (int k = 1; k <= 4; ++k) out[k] = (1.0 - alpha) * b[k] + 0.5 * alpha;
    return out;
}

const std::array<std::array<double, 4>, 4>& optimized_matrix() { return kT; }
const std::array<std::array<double, 4>, 4>& optimized_inverse() { return kTInverse; }

std::array<double, 4> optimized_encode(double z)
{
    const double m[4] = {z, z * z, z * z * z, z * z * z * z};
    std::array<double, 4> o{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) o[r] += kT[r][c] * m[c];
    o[0] += kOffset;
    return o;
}

std::array<std::uint32_t, 4> optimized_steps(double z)
{
    const std::array<double, 4> o = optimized_encode(z);
    std::array<std::uint32_t, 4> q{};
    for (int k = 0; k < 4; ++k) q[k] = std::uint32_t(std::floor(std::clamp(o[k], 0.0, 1.0) * 65535.0 + 0.5));
    return q;
}

Moments4 optimized_decode(const std::array<double, 4>& o)
{
    const double u[4] = {o[0] - kOffset, o[1], o[2], o[3]};
    Moments4 b{1.0, 0.0, 0.0, 0.0, 0.0};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) b[r + 1] += kTInverse[r][c] * u[c];
    return b;
}

BoundReference msm_bound(const Moments4& b, double z)
{
    if (z <= 0.0) return {0.0, false, {}};
    if (z > 1.0) return {1.0, false, {}};
    // Singular Hankel matrices: the distribution has one or two points and
    // its moments determine it.
    const double d2 = b[2] - b[1] * b[1];
    if (d2 <= 1e-13 * b[2]) return {b[1] < z ? 1.0 : 0.0, false, {{b[1], 1.0}}};
    const double e = b[3] - b[1] * b[2];
    const double d3 = (b[4] - b[2] * b[2]) - e * e / d2;
    if (d3 <= 1e-13 * b[4]) {
        const double sum = e / d2, product = (b[1] * b[3] - b[2] * b[2]) / d2;
        const double spread = std::sqrt(std::max(0.25 * sum * sum - product, 0.0));
        const std::vector<Atom> atoms = weights_at({0.5 * sum - spread, 0.5 * sum + spread}, b);
        return {mass_below(atoms, z), false, atoms};
    }
    const Mat hankel{{b[0], b[1], b[2]}, {b[1], b[2], b[3]}, {b[2], b[3], b[4]}};
    const Vec c = solve(hankel, {1.0, z, z * z});
    // Roots of c0 + c1 x + c2 x^2.
    const double disc = c[1] * c[1] - 4.0 * c[2] * c[0];
    if (disc >= 0.0 && c[2] != 0.0) {
        const double root = std::sqrt(disc);
        const double z2 = (-c[1] - std::copysign(root, c[2])) / (2.0 * c[2]);
        const double z3 = (-c[1] + std::copysign(root, c[2])) / (2.0 * c[2]);
        if (z2 >= 0.0 && z3 <= 1.0) {
            const std::vector<Atom> atoms = weights_at({z2, z, z3}, b);
            return {mass_below(atoms, z), false, atoms};
        }
    }
    // Hausdorff: {0, z, r, 1}, r from E[Z (Z - 1)(Z - z)(Z - r)] = 0, which is linear in r.
    const double a = b[3] - (1.0 + z) * b[2] + z * b[1];
    const double n = b[4] - (1.0 + z) * b[3] + z * b[2];
    const double r = n / a;
    const std::vector<Atom> atoms = weights_at({0.0, z, r, 1.0}, b);
    return {mass_below(atoms, z), true, atoms};
}

BlockerReference msm_blockers(const Moments4& b, double z)
{
    const Mat hankel{{b[0], b[1], b[2]}, {b[1], b[2], b[3]}, {b[2], b[3], b[4]}};
    const Vec c = solve(hankel, {1.0, z, z * z});
    const double disc = std::max(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0);
    const double root = std::sqrt(disc);
    const double z2 = (-c[1] - std::copysign(root, c[2])) / (2.0 * c[2]);
    const double z3 = (-c[1] + std::copysign(root, c[2])) / (2.0 * c[2]);
    const std::vector<Atom> atoms = weights_at({z2, z, z3}, b);
    double weight = 0.0, first = 0.0;
    for (const Atom& atom : atoms)
        if (atom.x < z) {
            weight += atom.w;
            first += atom.w * atom.x;
        }
    return {weight, weight > 0.0 ? first / weight : 0.0};
}

double lp_lower_bound(const Moments4& b, double z, const std::vector<double>& grid)
{
    // Tableau: 5 equality rows, columns = grid weights, then 5 artificials, then the right-hand side.
    const int m = 5, n = int(grid.size()), cols = n + m;
    Mat t(m, Vec(cols + 1, 0.0));
    for (int k = 0; k < m; ++k) {
        for (int j = 0; j < n; ++j) t[k][j] = std::pow(grid[j], double(k));
        t[k][n + k] = 1.0;
        t[k][cols] = b[k];
    }
    std::vector<int> basis(m);
    for (int k = 0; k < m; ++k) basis[k] = n + k;
    auto run = [&](const Vec& cost, int allowed) {
        for (int iteration = 0; iteration < 200000; ++iteration) {
            // Reduced costs; Bland's rule: the first improving column.
            int enter = -1;
            for (int j = 0; j < allowed && enter < 0; ++j) {
                double reduced = cost[j];
                for (int k = 0; k < m; ++k) reduced -= cost[basis[k]] * t[k][j];
                if (reduced < -1e-12) enter = j;
            }
            if (enter < 0) return;
            int leave = -1;
            double best = std::numeric_limits<double>::infinity();
            for (int k = 0; k < m; ++k)
                if (t[k][enter] > 1e-12) {
                    const double ratio = t[k][cols] / t[k][enter];
                    if (ratio < best - 1e-15 || (ratio <= best + 1e-15 && leave >= 0 && basis[k] < basis[leave])) {
                        best = ratio;
                        leave = k;
                    }
                }
            if (leave < 0) throw std::runtime_error("lp: unbounded");
            const double p = t[leave][enter];
            for (double& v : t[leave]) v /= p;
            for (int k = 0; k < m; ++k)
                if (k != leave) {
                    const double f = t[k][enter];
                    for (int j = 0; j <= cols; ++j) t[k][j] -= f * t[leave][j];
                }
            basis[leave] = enter;
        }
        throw std::runtime_error("lp: no convergence");
    };
    Vec phase1(cols, 0.0);
    for (int k = 0; k < m; ++k) phase1[n + k] = 1.0;
    run(phase1, cols);
    double infeasibility = 0.0;
    for (int k = 0; k < m; ++k)
        if (basis[k] >= n) infeasibility += t[k][cols];
    if (infeasibility > 1e-9) return -1.0;
    Vec phase2(cols, 0.0);
    for (int j = 0; j < n; ++j) phase2[j] = grid[j] < z ? 1.0 : 0.0;
    for (int k = 0; k < m; ++k) phase2[n + k] = 1e6;  // artificials stay out
    run(phase2, n);
    double value = 0.0;
    for (int k = 0; k < m; ++k) value += phase2[basis[k]] * t[k][cols];
    return value;
}

Moments4 table_moments(const MsmTable& table, int x0, int x1, int y0, int y1)
{
    const double area = double(x1 - x0) * (y1 - y0);
    std::array<double, 4> mean{};
    for (int k = 0; k < 4; ++k) {
        if (table.quantization == Quantization::Bits16)
            mean[k] = double(table.sums.exact_box_sum(k + 1, x0, x1, y0, y1)) / 65535.0 / area;
        else
            mean[k] = table.sums.box_sum(k + 1, x0, x1, y0, y1) / area;
    }
    if (table.quantization == Quantization::Bits16) return optimized_decode(mean);
    return {1.0, mean[0], mean[1], mean[2], mean[3]};
}

}  // namespace penumbra::testing
