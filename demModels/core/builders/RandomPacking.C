#include "RandomPacking.H"

#include "Dictionary.H"

#include "CellGrid.H"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace iceDEM
{

namespace
{

constexpr double pi = 3.14159265358979323846;

//- Densest sphere packing is pi / sqrt(18) = 0.7405; the spec asks for less.
constexpr double maxSolidFraction = 0.74;

//- Over-relaxation of the Gauss-Seidel pair projections: of 1.0 - 1.8, 1.6 reached the densest
//  packings in the fewest sweeps.
constexpr double overRelaxation = 1.6;

//- Neighbour-list skin, as a fraction of the mean radius.
constexpr double skinFraction = 0.2;

//- Sweeps between two looks at the convergence rate.
constexpr int checkWindow = 50;

//- Aim to reach the tolerance within this fraction of maxIterations; a slower predicted
//  convergence means the packing is near jamming and the radii shrink a little.
constexpr double convergenceBudget = 0.5;

//- Radius shrink per window: starts small, grows by shrinkGrowth while shrinking goes on.
constexpr double firstShrinkStep = 0.001;
constexpr double shrinkGrowth = 1.5;
constexpr double maxShrinkStep = 0.01;

double sphereVolume(double r)
{
    return 4.0/3.0*pi*r*r*r;
}

//- Uniform in [0, 1) from the top 53 bits: the same on every platform and library version.
double uniform01(std::mt19937_64& rng)
{
    return static_cast<double>(rng() >> 11)*0x1.0p-53;
}

void invalid(const std::string& what)
{
    throw std::invalid_argument("random packing: " + what);
}

void validate(const RandomPackingSpec& spec)
{
    if (spec.particleCount < 1)
    {
        invalid("particleCount must be at least 1 (got " + std::to_string(spec.particleCount) + ")");
    }
    for (int k = 0; k < 3; ++k)
    {
        if (!(spec.hi[k] > spec.lo[k]))
        {
            std::ostringstream os;
            os << "empty box: hi must exceed lo on every axis (axis " << k << ": lo "
               << spec.lo[k] << ", hi " << spec.hi[k] << ")";
            invalid(os.str());
        }
    }
    if (!(spec.targetSolidFraction > 0.0 && spec.targetSolidFraction < maxSolidFraction))
    {
        invalid("targetSolidFraction must lie in (0, 0.74) (got "
            + std::to_string(spec.targetSolidFraction) + ")");
    }
    if (!(spec.radiusSpread >= 0.0 && spec.radiusSpread < 1.0))
    {
        invalid("radiusSpread must lie in [0, 1) (got " + std::to_string(spec.radiusSpread) + ")");
    }
    if (spec.maxIterations < 0)
    {
        invalid("maxIterations must not be negative (got " + std::to_string(spec.maxIterations) + ")");
    }
    if (!(spec.overlapTolerance > 0.0))
    {
        invalid("overlapTolerance must be positive (got " + std::to_string(spec.overlapTolerance) + ")");
    }
}

//- Radii drawn uniformly within (1 +- spread) of a nominal radius chosen so that the total sphere
//  volume is the target fraction of the box volume. Returns the nominal radius.
double drawRadii(const RandomPackingSpec& spec, std::mt19937_64& rng, std::vector<double>& radii)
{
    radii.resize(spec.particleCount);
    double unitVolume = 0.0;
    for (double& r : radii)
    {
        r = 1.0 + spec.radiusSpread*(2.0*uniform01(rng) - 1.0);
        unitVolume += sphereVolume(r);
    }
    const Vec3 size = spec.hi - spec.lo;
    const double nominal = std::cbrt(spec.targetSolidFraction*size.prod()/unitVolume);
    for (double& r : radii)
    {
        r *= nominal;
    }

    const double maxDiameter = 2.0*(*std::max_element(radii.begin(), radii.end()));
    if (maxDiameter >= size.minCoeff())
    {
        std::ostringstream os;
        os << "box thinner than a particle diameter: " << spec.particleCount
           << " particles at solid fraction " << spec.targetSolidFraction
           << " need diameters up to " << maxDiameter << " but the box is only " << size.minCoeff()
           << " thick; raise particleCount or lower targetSolidFraction";
        invalid(os.str());
    }
    return nominal;
}

//- A fixed pseudo-random unit vector for a pair, used only when two centres coincide.
Vec3 pairDirection(int i, int j)
{
    std::mt19937_64 rng(static_cast<std::uint64_t>(i)*0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(j));
    const double z = 2.0*uniform01(rng) - 1.0;
    const double phi = 2.0*pi*uniform01(rng);
    const double s = std::sqrt(1.0 - z*z);
    return Vec3(s*std::cos(phi), s*std::sin(phi), z);
}

//- Verlet list of the pairs closer than r_i + r_j + skin; rebuilt when a particle has moved more
//  than skin/2 since the last build. Radii only shrink, so a list stays complete until then.
class NeighbourList
{
public:
    NeighbourList(CellGrid& grid, double skin)
    :
        grid_(grid),
        skin_(skin)
    {}

    const std::vector<std::pair<int, int>>& pairs
    (
        const std::vector<Vec3>& positions,
        const std::vector<double>& radii
    )
    {
        if (stale(positions))
        {
            build(positions, radii);
        }
        return pairs_;
    }

private:
    bool stale(const std::vector<Vec3>& positions) const
    {
        if (builtAt_.size() != positions.size())
        {
            return true;
        }
        const double limit2 = 0.25*skin_*skin_;
        for (std::size_t i = 0; i < positions.size(); ++i)
        {
            if ((positions[i] - builtAt_[i]).squaredNorm() > limit2)
            {
                return true;
            }
        }
        return false;
    }

    void build(const std::vector<Vec3>& positions, const std::vector<double>& radii)
    {
        grid_.build(positions);
        pairs_.clear();
        grid_.forEachPair([&](int i, int j)
        {
            const double reach = radii[i] + radii[j] + skin_;
            if ((positions[j] - positions[i]).squaredNorm() < reach*reach)
            {
                pairs_.emplace_back(i, j);
            }
        });
        builtAt_ = positions;
    }

    CellGrid& grid_;
    double skin_;
    std::vector<std::pair<int, int>> pairs_;
    std::vector<Vec3> builtAt_;
};

//- Positions and radii being relaxed inside the box.
class Packing
{
public:
    Packing(const RandomPackingSpec& spec, std::vector<double> radii, std::mt19937_64& rng)
    :
        lo_(spec.lo),
        hi_(spec.hi),
        radii_(std::move(radii)),
        positions_(radii_.size())
    {
        for (std::size_t i = 0; i < radii_.size(); ++i)
        {
            for (int k = 0; k < 3; ++k)
            {
                const double span = hi_[k] - lo_[k] - 2.0*radii_[i];
                positions_[i][k] = lo_[k] + radii_[i] + span*uniform01(rng);
            }
        }
    }

    //- One Gauss-Seidel sweep pushing every overlapping pair apart symmetrically.
    //  Returns the largest overlap met (before its correction).
    double relax(NeighbourList& list)
    {
        double maxOverlap = 0.0;
        for (const auto& [i, j] : list.pairs(positions_, radii_))
        {
            const Vec3 dx = positions_[j] - positions_[i];
            const double contact = radii_[i] + radii_[j];
            const double d2 = dx.squaredNorm();
            if (d2 >= contact*contact)
            {
                continue;
            }
            const double d = std::sqrt(d2);
            const double overlap = contact - d;
            maxOverlap = std::max(maxOverlap, overlap);
            const Vec3 n = d > 1e-12*contact ? Vec3(dx/d) : pairDirection(i, j);
            const Vec3 push = 0.5*overRelaxation*overlap*n;
            positions_[i] -= push;
            positions_[j] += push;
            clamp(i);
            clamp(j);
        }
        return maxOverlap;
    }

    //- Largest overlap of the current positions (negative: the closest gap), moving nothing.
    double maxOverlap(CellGrid& grid) const
    {
        grid.build(positions_);
        double maxOverlap = -std::numeric_limits<double>::max();
        grid.forEachPair([&](int i, int j)
        {
            const double d = (positions_[j] - positions_[i]).norm();
            maxOverlap = std::max(maxOverlap, radii_[i] + radii_[j] - d);
        });
        return maxOverlap;
    }

    //- Largest uniform radius scale (<= 1) that brings every overlap to at most
    //  tolerance * mean radius.
    double scaleForTolerance(CellGrid& grid, double tolerance) const
    {
        grid.build(positions_);
        const double allowed = tolerance*meanRadius();
        double scale = 1.0;
        grid.forEachPair([&](int i, int j)
        {
            const double d = (positions_[j] - positions_[i]).norm();
            const double contact = radii_[i] + radii_[j];
            if (contact - d > allowed)
            {
                scale = std::min(scale, d/(contact - allowed));
            }
        });
        return scale < 1.0 ? scale*(1.0 - 1e-9) : 1.0;
    }

    void scaleRadii(double factor)
    {
        for (double& r : radii_)
        {
            r *= factor;
        }
    }

    double meanRadius() const
    {
        return std::accumulate(radii_.begin(), radii_.end(), 0.0)/radii_.size();
    }

    double maxRadius() const
    {
        return *std::max_element(radii_.begin(), radii_.end());
    }

    const std::vector<double>& radii() const { return radii_; }
    const std::vector<Vec3>& positions() const { return positions_; }

private:
    //- Keep sphere i fully inside the box.
    void clamp(int i)
    {
        for (int k = 0; k < 3; ++k)
        {
            positions_[i][k] = std::clamp(positions_[i][k], lo_[k] + radii_[i], hi_[k] - radii_[i]);
        }
    }

    Vec3 lo_;
    Vec3 hi_;
    std::vector<double> radii_;
    std::vector<Vec3> positions_;
};

//- Decides, once per check window, whether the relaxation would reach the tolerance in time, and
//  if not by how much to shrink the radii: a small step first, growing while shrinking goes on.
class ShrinkSchedule
{
public:
    explicit ShrinkSchedule(int maxIterations)
    :
        targetIterations_(convergenceBudget*maxIterations)
    {}

    //- Radius factor (1: no shrink) at the end of a window.
    double factor(int iterations, double overlap, double tolerance, double meanRadius)
    {
        const double previous = windowStartOverlap_;
        windowStartOverlap_ = overlap;
        if (previous <= 0.0 || !tooSlow(iterations, previous, overlap, tolerance))
        {
            step_ = 0.0;
            return 1.0;
        }
        step_ = step_ == 0.0 ? firstShrinkStep : std::min(maxShrinkStep, shrinkGrowth*step_);
        // Never shrink much beyond what would clear the largest overlap.
        return 1.0 - std::min(step_, 0.1*overlap/meanRadius);
    }

private:
    bool tooSlow(int iterations, double previous, double overlap, double tolerance) const
    {
        const double rate = overlap/previous;
        if (rate >= 1.0)
        {
            return true;
        }
        const double remainingWindows = std::log(tolerance/overlap)/std::log(rate);
        return iterations + checkWindow*remainingWindows > targetIterations_;
    }

    double targetIterations_;
    double windowStartOverlap_ = -1.0;
    double step_ = 0.0;
};

RandomPackingStats measure(const Packing& packing, const RandomPackingSpec& spec, double maxOverlap)
{
    RandomPackingStats stats;
    const std::vector<double>& radii = packing.radii();
    double volume = 0.0;
    for (double r : radii)
    {
        volume += sphereVolume(r);
    }
    stats.solidFraction = volume/(spec.hi - spec.lo).prod();
    stats.meanRadius = packing.meanRadius();
    stats.minRadius = *std::min_element(radii.begin(), radii.end());
    stats.maxRadius = packing.maxRadius();
    stats.maxOverlap = std::max(0.0, maxOverlap)/stats.meanRadius;
    return stats;
}

} // namespace


RandomPackingChoice RandomPackingChoice::read(const Dictionary& d)
{
    RandomPackingChoice c;
    c.radiusSpread = d.getScalarOrDefault("radiusSpread", c.radiusSpread);
    if (c.radiusSpread < 0.0 || c.radiusSpread >= 0.9)
    {
        d.fail("radiusSpread", "expected a relative half-width in [0, 0.9)");
    }
    c.solidFraction = d.getScalarOrDefault("solidFraction", c.solidFraction);
    if (c.solidFraction <= 0.0 || c.solidFraction > randomClosePackingFraction)
    {
        d.fail("solidFraction", "expected a solid fraction in (0, 0.64]: a random packing cannot be "
               "denser than random close packing (0.64)");
    }
    c.seed = static_cast<unsigned>(d.getLabelOrDefault("seed", static_cast<int>(c.seed)));
    return c;
}


std::vector<ParticleSpec> buildRandomPacking(const RandomPackingSpec& spec, RandomPackingStats& stats)
{
    validate(spec);

    std::mt19937_64 rng(spec.seed);
    std::vector<double> radii;
    const double nominalRadius = drawRadii(spec, rng, radii);
    Packing packing(spec, std::move(radii), rng);

    // Radii only ever shrink, so a grid sized for the initial ones stays valid.
    const double skin = skinFraction*packing.meanRadius();
    CellGrid grid(spec.lo, spec.hi, 2.0*packing.maxRadius() + skin);
    NeighbourList neighbours(grid, skin);
    ShrinkSchedule schedule(spec.maxIterations);

    double radiusScale = 1.0;
    int iterations = 0;
    bool converged = false;
    while (iterations < spec.maxIterations)
    {
        const double sweepOverlap = packing.relax(neighbours);
        ++iterations;
        const double tolerance = spec.overlapTolerance*packing.meanRadius();
        if (sweepOverlap <= tolerance && packing.maxOverlap(grid) <= tolerance)
        {
            converged = true;
            break;
        }
        if (iterations % checkWindow == 0)
        {
            const double factor =
                schedule.factor(iterations, sweepOverlap, tolerance, packing.meanRadius());
            packing.scaleRadii(factor);
            radiusScale *= factor;
        }
    }
    if (!converged)
    {
        // Out of sweeps: shrink just enough to meet the tolerance, so the result always does.
        const double factor = packing.scaleForTolerance(grid, spec.overlapTolerance);
        packing.scaleRadii(factor);
        radiusScale *= factor;
    }

    stats = measure(packing, spec, packing.maxOverlap(grid));
    stats.nominalRadius = nominalRadius;
    stats.radiusScale = radiusScale;
    stats.iterations = iterations;
    stats.converged = converged;

    std::vector<ParticleSpec> particles(spec.particleCount);
    for (int i = 0; i < spec.particleCount; ++i)
    {
        particles[i].position = packing.positions()[i];
        particles[i].radius = packing.radii()[i];
    }
    return particles;
}


int particleCountForDiameter
(
    const Vec3& lo,
    const Vec3& hi,
    double meanDiameter,
    double radiusSpread,
    double solidFraction
)
{
    if (!(meanDiameter > 0.0) || !(solidFraction > 0.0) || radiusSpread < 0.0 || radiusSpread >= 1.0)
    {
        invalid("the mean diameter and solid fraction must be positive, the radius spread in [0, 1)");
    }
    // Mean sphere volume of radii uniform in r0 (1 -+ s): r0^3 (1 + s^2).
    const double r0 = 0.5 * meanDiameter;
    const double meanVolume = 4.0 / 3.0 * M_PI * r0 * r0 * r0 * (1.0 + radiusSpread * radiusSpread);
    const double boxVolume = (hi - lo).prod();
    return std::max(1, static_cast<int>(std::lround(solidFraction * boxVolume / meanVolume)));
}


std::vector<ParticleSpec> buildRandomPacking(const RandomPackingSpec& spec)
{
    RandomPackingStats stats;
    return buildRandomPacking(spec, stats);
}


void markFixedEnds
(
    std::vector<ParticleSpec>& particles,
    int axis,
    double padLength,
    const Vec3& lo,
    const Vec3& hi
)
{
    if (axis < 0 || axis > 2)
    {
        throw std::invalid_argument("markFixedEnds: axis must be 0, 1 or 2 (got " + std::to_string(axis) + ")");
    }
    if (!(padLength >= 0.0))
    {
        throw std::invalid_argument("markFixedEnds: padLength must not be negative");
    }
    for (ParticleSpec& p : particles)
    {
        const double x = p.position[axis];
        if (x - lo[axis] <= padLength || hi[axis] - x <= padLength)
        {
            p.fixed = true;
        }
    }
}

} // namespace iceDEM
