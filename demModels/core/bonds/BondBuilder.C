#include "BondBuilder.H"
#include "CellGrid.H"
#include "InputError.H"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

namespace
{

const char* const propertiesFile = "constant/iceProperties";

void checkParticles(const std::vector<ParticleSpec>& particles)
{
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        const ParticleSpec& p = particles[i];
        if (!(std::isfinite(p.radius) && p.radius > 0.0) || !p.position.allFinite())
        {
            std::ostringstream os;
            os << "bond builder: particle " << i << " has radius " << p.radius << " at ("
               << p.position.transpose() << "); radii must be positive and positions finite";
            throw std::invalid_argument(os.str());
        }
    }
}

std::string vectorText(const Vec3& v)
{
    std::ostringstream os;
    os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return os.str();
}

} // namespace


BondFamily bondFamily(const ParticleSpec& a, const ParticleSpec& b)
{
    return a.block == b.block ? BondFamily::ice : BondFamily::freeze;
}


BondBuilder::BondBuilder(const IceProperties& ice)
:
    maxBondsPerParticle_(ice.maxBondsPerParticle)
{
    for (int f = 0; f < nBondFamilies; ++f)
    {
        const BondFamily family = static_cast<BondFamily>(f);
        distFactors_[f] = ice.family(family).distFactor;
        if (!(std::isfinite(distFactors_[f]) && distFactors_[f] > 0.0))
        {
            throw InputError
            (
                propertiesFile,
                "bondFamilies." + toString(family) + ".distFactor",
                "must be a positive number (got " + std::to_string(distFactors_[f]) + ")"
            );
        }
    }
}


BondBuilder& BondBuilder::skipFixedPairs(bool skip)
{
    skipFixedPairs_ = skip;
    return *this;
}


std::vector<BondPair> BondBuilder::build(const std::vector<ParticleSpec>& particles)
{
    checkParticles(particles);
    std::vector<BondPair> bonds;
    if (particles.empty())
    {
        statistics_ = bondStatistics(bonds, 0);
        return bonds;
    }

    std::vector<Vec3> positions(particles.size());
    double maxRadius = 0.0;
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        positions[i] = particles[i].position;
        maxRadius = std::max(maxRadius, particles[i].radius);
    }
    const double maxFactor = *std::max_element(distFactors_.begin(), distFactors_.end());
    CellGrid::around(positions, 2.0*maxFactor*maxRadius).forEachPair([&](int a, int b)
    {
        const ParticleSpec& pa = particles[a];
        const ParticleSpec& pb = particles[b];
        if (skipFixedPairs_ && pa.fixed && pb.fixed)
        {
            return;
        }
        const BondFamily family = bondFamily(pa, pb);
        const double reach = distFactors_[static_cast<int>(family)]*(pa.radius + pb.radius);
        const double d2 = (pb.position - pa.position).squaredNorm();
        // Cheap rejection with a margin, so the rule is decided on d itself, not on d^2.
        if (d2 > (1.0 + 1e-12)*reach*reach)
        {
            return;
        }
        const double d = std::sqrt(d2);
        if (d <= reach)
        {
            bonds.push_back({std::min(a, b), std::max(a, b), family, d});
        }
    });
    std::sort(bonds.begin(), bonds.end(), [](const BondPair& x, const BondPair& y)
    {
        return x.i < y.i || (x.i == y.i && x.j < y.j);
    });

    statistics_ = bondStatistics(bonds, static_cast<int>(particles.size()));
    if (statistics_.maxBondsPerParticle > maxBondsPerParticle_)
    {
        std::vector<int> count(particles.size(), 0);
        for (const BondPair& b : bonds)
        {
            ++count[b.i];
            ++count[b.j];
        }
        const auto first = std::find_if(count.begin(), count.end(), [&](int c)
        {
            return c > maxBondsPerParticle_;
        });
        const std::size_t k = first - count.begin();
        const long over = std::count_if(count.begin(), count.end(), [&](int c)
        {
            return c > maxBondsPerParticle_;
        });
        std::ostringstream os;
        os << "particle " << k << " at " << vectorText(particles[k].position) << " would need "
           << count[k] << " bonds, more than the " << maxBondsPerParticle_ << " allowed ("
           << over << " particle(s) exceed it, up to " << statistics_.maxBondsPerParticle
           << " bonds); raise maxBondsPerParticle or lower distFactor (ice "
           << distFactors_[static_cast<int>(BondFamily::ice)] << ", freeze "
           << distFactors_[static_cast<int>(BondFamily::freeze)] << ")";
        throw InputError(propertiesFile, "maxBondsPerParticle", os.str());
    }
    return bonds;
}


BondStatistics bondStatistics(const std::vector<BondPair>& bonds, int particleCount)
{
    BondStatistics s;
    s.particleCount = particleCount;
    s.totalBonds = static_cast<int>(bonds.size());
    std::vector<int> count(particleCount, 0);
    for (const BondPair& b : bonds)
    {
        if (b.i < 0 || b.j < 0 || b.i >= particleCount || b.j >= particleCount)
        {
            throw std::invalid_argument
            (
                "bond statistics: bond (" + std::to_string(b.i) + ", " + std::to_string(b.j)
              + ") refers to a particle outside 0.." + std::to_string(particleCount - 1)
            );
        }
        ++s.bondsPerFamily[static_cast<int>(b.family)];
        ++count[b.i];
        ++count[b.j];
    }
    if (particleCount > 0)
    {
        s.minBondsPerParticle = *std::min_element(count.begin(), count.end());
        s.maxBondsPerParticle = *std::max_element(count.begin(), count.end());
        s.meanBondsPerParticle = 2.0*s.totalBonds/particleCount;
    }
    s.histogram.assign(s.maxBondsPerParticle + 1, 0);
    for (int c : count)
    {
        ++s.histogram[c];
    }
    return s;
}


std::string BondStatistics::summary() const
{
    std::ostringstream os;
    os << totalBonds << " bonds (";
    for (int f = 0; f < nBondFamilies; ++f)
    {
        os << (f ? ", " : "") << toString(static_cast<BondFamily>(f)) << " " << bondsPerFamily[f];
    }
    os << ") on " << particleCount << " particles; per particle mean " << std::fixed
       << std::setprecision(2) << meanBondsPerParticle << ", min " << minBondsPerParticle
       << ", max " << maxBondsPerParticle << "; histogram (bonds:particles)";
    for (std::size_t k = 0; k < histogram.size(); ++k)
    {
        if (histogram[k] > 0)
        {
            os << " " << k << ":" << histogram[k];
        }
    }
    return os.str();
}

std::vector<BondState> newBondStates
(
    const std::vector<BondPair>& pairs,
    const std::vector<ParticleSpec>& particles,
    const IceProperties& ice
)
{
    const BondModel models[nBondFamilies] =
    {
        BondModel(ice.family(BondFamily::ice), ice.damping),
        BondModel(ice.family(BondFamily::freeze), ice.damping)
    };
    auto state = [&](int index)
    {
        ParticleState p;
        p.position = particles[index].position;
        p.radius = particles[index].radius;
        return p;
    };
    std::vector<BondState> states;
    states.reserve(pairs.size());
    for (const BondPair& pair : pairs)
    {
        BondState s = models[static_cast<int>(pair.family)].create(pair.i + 1, pair.j + 1, state(pair.i), state(pair.j));
        s.family = pair.family;
        states.push_back(s);
    }
    return states;
}

} // namespace iceDEM
