#include "FreezeBonding.H"

#include "InputError.H"

#include "CellGrid.H"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace iceDEM
{

double bondArea(const BondFamilyParameters& f, double ra, double rb)
{
    const double r = f.radiusMultiplier*std::min(ra, rb);
    return M_PI*r*r;
}


std::vector<NewFreezeBond> freezeBondsAtContacts
(
    const std::vector<ParticleSpec>& particles,
    const IceProperties& ice,
    const FreezeBondProperties& freezeBondProperties,
    double contactNormalStiffness
)
{
    std::vector<NewFreezeBond> bonds;
    if (particles.empty())
    {
        return bonds;
    }
    const BondFamilyParameters& family = ice.family(BondFamily::freeze);
    double maxRadius = 0.0;
    std::vector<Vec3> positions;
    positions.reserve(particles.size());
    for (const ParticleSpec& p : particles)
    {
        maxRadius = std::max(maxRadius, p.radius);
        positions.push_back(p.position);
    }
    CellGrid::around(positions, 2.0*maxRadius*family.distFactor).forEachPair([&](int a, int b)
    {
        const ParticleSpec& pa = particles[a];
        const ParticleSpec& pb = particles[b];
        if (pa.block == pb.block)
        {
            return;
        }
        const double distance = (pb.position - pa.position).norm();
        const double touch = pa.radius + pb.radius;
        if (distance > family.distFactor*touch)
        {
            return;
        }
        NewFreezeBond bond;
        bond.pair = {std::min(a, b), std::max(a, b), BondFamily::freeze, distance};
        bond.contactForce = contactNormalStiffness*std::max(0.0, touch - distance);
        bond.strength = freezeBondProperties.strength(bond.contactForce, bondArea(family, pa.radius, pb.radius));
        bonds.push_back(bond);
    });
    std::sort(bonds.begin(), bonds.end(), [](const NewFreezeBond& x, const NewFreezeBond& y)
    {
        return std::make_pair(x.pair.i, x.pair.j) < std::make_pair(y.pair.i, y.pair.j);
    });
    return bonds;
}


std::vector<BondState> freezeBondStates
(
    const std::vector<NewFreezeBond>& bonds,
    const std::vector<ParticleSpec>& now,
    const IceProperties& ice
)
{
    std::vector<BondPair> pairs;
    for (const NewFreezeBond& b : bonds)
    {
        pairs.push_back(b.pair);
    }
    std::vector<BondState> states = newBondStates(pairs, now, ice);
    for (std::size_t k = 0; k < bonds.size(); ++k)
    {
        states[k].tensileStrength = bonds[k].strength.tensile;
        states[k].shearStrength = bonds[k].strength.shear;
    }
    return states;
}


FreezeBondingStatistics freezeBondingStatistics
(
    const std::vector<NewFreezeBond>& bonds,
    const std::vector<ParticleSpec>& particles
)
{
    FreezeBondingStatistics s;
    s.bonds = static_cast<int>(bonds.size());
    if (bonds.empty())
    {
        return s;
    }
    std::set<std::pair<int, int>> blockPairs;
    double sumT = 0, sumT2 = 0, sumS = 0, sumS2 = 0, sumP = 0, sumET = 0, sumES = 0;
    for (const NewFreezeBond& b : bonds)
    {
        const int ba = particles[b.pair.i].block, bb = particles[b.pair.j].block;
        blockPairs.insert({std::min(ba, bb), std::max(ba, bb)});
        sumT += b.strength.tensile;
        sumT2 += b.strength.tensile*b.strength.tensile;
        sumS += b.strength.shear;
        sumS2 += b.strength.shear*b.strength.shear;
        sumP += b.strength.confinement;
        sumET += b.strength.effectiveTensile;
        sumES += b.strength.effectiveShear;
        s.maxConfinement = std::max(s.maxConfinement, b.strength.confinement);
    }
    const double n = s.bonds;
    s.blockContacts = static_cast<int>(blockPairs.size());
    s.meanBondsPerBlockContact = n/s.blockContacts;
    s.meanTensile = sumT/n;
    s.sdTensile = std::sqrt(std::max(0.0, sumT2/n - s.meanTensile*s.meanTensile));
    s.meanShear = sumS/n;
    s.sdShear = std::sqrt(std::max(0.0, sumS2/n - s.meanShear*s.meanShear));
    s.meanConfinement = sumP/n;
    s.meanEffectiveTensile = sumET/n;
    s.meanEffectiveShear = sumES/n;
    return s;
}

void requireFreezeBondStrengthsPerBond(const IceProperties& ice, const std::string& iceFile)
{
    if (ice.family(BondFamily::freeze).strengthModel != StrengthModel::perBond)
    {
        throw InputError(iceFile, "bondFamilies.freeze.strengthModel",
            "must be freezeBondProperties: freeze-bond strengths come from constant/freezeBondProperties");
    }
}

} // namespace iceDEM
