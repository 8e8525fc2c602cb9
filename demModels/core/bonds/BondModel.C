#include "BondModel.H"

#include "BondBatches.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace iceDEM
{

namespace
{

double ratio(double load, double limit)
{
    return limit > 0.0 ? load / limit : 0.0;
}

} // namespace


BondStiffness BondStiffness::of
(
    const BondFamilyParameters& family,
    double radiusA,
    double radiusB
)
{
    BondStiffness k;
    k.bondRadius = family.radiusMultiplier * std::min(radiusA, radiusB);
    const double rb2 = k.bondRadius * k.bondRadius;
    k.area = M_PI * rb2;
    k.area15 = k.area * std::sqrt(k.area);
    k.inertia = M_PI * rb2 * rb2 / 4.0;
    k.polarInertia = 2.0 * k.inertia;
    k.beamLength = radiusA + radiusB;
    // Both particles carry the family's modulus, so E_eq = (r_a + r_b)/(r_a/E + r_b/E) = E.
    k.youngsModulus = family.youngsModulus;
    k.shearModulus = k.youngsModulus / (2.0 * (1.0 + family.poissonsRatio));
    k.normal = k.youngsModulus * k.area / k.beamLength;
    k.normalCompression = family.compressionModulusOrYoungs() * k.area / k.beamLength;
    k.shear = k.shearModulus * k.area / k.beamLength;
    k.twist = k.shearModulus * k.polarInertia / k.beamLength;
    k.bending = k.youngsModulus * k.inertia / k.beamLength;
    return k;
}


BondModel::BondModel(const BondFamilyParameters& family, DampingParameters damping)
:
    family_(family),
    damping_(damping)
{}


BondState BondModel::create
(
    long tagA,
    long tagB,
    const ParticleState& a,
    const ParticleState& b
) const
{
    BondState state;
    state.tagA = tagA;
    state.tagB = tagB;
    state.restLength = (b.position - a.position).norm();
    if (family_.strengthModel == StrengthModel::strain)
    {
        const BondStiffness k = BondStiffness::of(family_, a.radius, b.radius);
        state.tensileStrength = family_.breakN * k.youngsModulus;
        state.shearStrength = family_.beta * state.tensileStrength;
    }
    else if (family_.strengthModel == StrengthModel::stress)
    {
        state.tensileStrength = family_.tensileStrength;
        state.shearStrength = family_.shearStrength;
    }
    // perBond: the creator sets the strengths; until then the bond has none.
    return state;
}


BreakMode BondModel::breakage
(
    const BondState& state,
    const BondStiffness& k,
    double normalForce,
    double shearForce,
    double twistTorque,
    double bendingTorque
) const
{
    if (family_.unbreakable)
    {
        return BreakMode::none;
    }

    const double sigmaT = state.tensileStrength;
    const double tau = state.shearStrength;
    const double area15 = k.area15;

    BreakMode mode = BreakMode::none;
    double worst = 1.0;
    auto consider = [&](BreakMode candidate, double r)
    {
        if (r >= worst)
        {
            worst = r;
            mode = candidate;
        }
    };

    if (family_.criterion == BreakageCriterion::separate)
    {
        consider(BreakMode::tension, ratio(normalForce, sigmaT * k.area));
        consider(BreakMode::shear, ratio(shearForce, tau * k.area));
        consider(BreakMode::twist, ratio(twistTorque, family_.twistStrengthFactor * tau * area15));
        consider(BreakMode::bending, ratio(bendingTorque, family_.bendingStrengthFactor * sigmaT * area15));
        return mode;
    }

    // Combined (parallel-bond) criterion: peak fibre stresses of a beam under
    // axial force + bending, and shear + twist.
    const double tensileStress = normalForce / k.area;
    const double bendingStress = bendingTorque * k.bondRadius / k.inertia;
    const double shearStress = shearForce / k.area;
    const double twistStress = twistTorque * k.bondRadius / k.polarInertia;
    consider
    (
        tensileStress >= bendingStress ? BreakMode::tension : BreakMode::bending,
        ratio(tensileStress + bendingStress, sigmaT)
    );
    consider
    (
        shearStress >= twistStress ? BreakMode::shear : BreakMode::twist,
        ratio(shearStress + twistStress, tau)
    );
    return mode;
}


BondLoad BondModel::evaluate
(
    BondState& state,
    const ParticleState& a,
    const ParticleState& b,
    double dt
) const
{
    return evaluate(state, BondStiffness::of(family_, a.radius, b.radius), a, b, dt);
}


BondLoad BondModel::evaluate
(
    BondState& state,
    const BondStiffness& k,
    const ParticleState& a,
    const ParticleState& b,
    double dt
) const
{
    // The bond alone in every lane of the runs' kernel, so that one-bond
    // callers (the unit tests, SerialBondedSystem) step it with the very
    // arithmetic the runs use. Every lane writes the same loads to the same two slots.
    const KernelAtom atoms[2] = {kernelAtomOf(a), kernelAtomOf(b)};
    BondBatches bond;
    bond.resize(1);
    const double noScreen = -std::numeric_limits<double>::infinity();   // breakMode below decides
    bond.set(0, 0, 1, state, k, {noScreen, noScreen, noScreen, noScreen});
    bond.setLoadSlots(0, 0, 1);
    bond.pad();
    BondEndLoad ends[2];

    BondKernelSettings settings;
    settings.dt = dt;
    settings.viscous = damping_.model == DampingModel::viscous && damping_.dampingRatio > 0.0;
    settings.dampingRatio = damping_.dampingRatio;
    static const BondKernel kernel = bestBondKernel();
    BondKernelResult result;
    kernel(atoms, bond.batch(0), ends, settings, result);
    bond.copyHistory(0, state);
    BondLoad load;
    load.centre = Vec3(result.centre[0][0], result.centre[1][0], result.centre[2][0]);
    // The limits apply to the spring loads, before any viscous damping.
    load.broke = breakMode
    (
        state, k, result.springNormalForce[0], result.shearForce2[0], result.twistTorque2[0], result.bendingTorque2[0]
    );
    if (load.broke == BreakMode::none)
    {
        load.springNormalForce = result.springNormalForce[0];
        load.forceOnA = Vec3(ends[0].force[0], ends[0].force[1], ends[0].force[2]);
        load.torqueOnA = Vec3(ends[0].moment[0], ends[0].moment[1], ends[0].moment[2]);
        load.torqueOnB = Vec3(ends[1].moment[0], ends[1].moment[1], ends[1].moment[2]);
    }
    return load;
}


double BondModel::potentialEnergy
(
    const BondState& state,
    const ParticleState& a,
    const ParticleState& b
) const
{
    const BondStiffness k = BondStiffness::of(family_, a.radius, b.radius);
    const double stretch = (b.position - a.position).norm() - state.restLength;
    return 0.5 *
    (
        (stretch > 0.0 ? k.normal : k.normalCompression) * stretch * stretch
      + k.shear * state.shearDisplacement.squaredNorm()
      + k.twist * state.twistAngle * state.twistAngle
      + k.bending * state.bendingAngle.squaredNorm()
    );
}

} // namespace iceDEM
