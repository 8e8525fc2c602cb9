#include "BondModel.H"

#include <cmath>

namespace iceDEM
{

namespace
{

double ratio(double load, double limit)
{
    return limit > 0.0 ? load / limit : 0.0;
}

} // namespace


Vec3 rotateIntoTangentPlane(const Vec3& stored, const Vec3& n)
{
    const Vec3 projected = stored - stored.dot(n) * n;
    const double projected2 = projected.squaredNorm();
    if (projected2 <= 0.0)
    {
        return Vec3::Zero();
    }
    return projected * std::sqrt(stored.squaredNorm() / projected2);
}


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
    k.armFractionA = radiusA / k.beamLength;
    // Both particles carry the family's modulus, so E_eq = (r_a + r_b)/(r_a/E + r_b/E) = E.
    k.youngsModulus = family.youngsModulus;
    k.shearModulus = k.youngsModulus / (2.0 * (1.0 + family.poissonsRatio));
    k.normal = k.youngsModulus * k.area / k.beamLength;
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
    else
    {
        state.tensileStrength = family_.tensileStrength;
        state.shearStrength = family_.shearStrength;
    }
    return state;
}


bool BondModel::surelyIntact
(
    const BondState& state,
    const BondStiffness& k,
    double normalForce,
    double shearForce2,
    double twistTorque2,
    double bendingTorque2
) const
{
    // Below this fraction of a limit, round-off cannot make the exact ratio reach 1.
    constexpr double margin = 0.99;
    auto square = [](double x) { return x * x; };
    const double sigmaT = margin * state.tensileStrength;
    const double tau = margin * state.shearStrength;
    if (family_.criterion == BreakageCriterion::separate)
    {
        return normalForce < sigmaT * k.area
            && shearForce2 < square(tau * k.area)
            && twistTorque2 < square(family_.twistStrengthFactor * tau * k.area15)
            && bendingTorque2 < square(family_.bendingStrengthFactor * sigmaT * k.area15);
    }
    // Combined: sigma + bending stress < sigma_t, and (shear + twist stress)^2,
    // which is at most twice the sum of their squares, < tau^2.
    const double tensionReserve = sigmaT - normalForce / k.area;
    return tensionReserve > 0.0
        && bendingTorque2 * square(k.bondRadius / k.inertia) < square(tensionReserve)
        && 2.0 * (shearForce2 / square(k.area) + twistTorque2 * square(k.bondRadius / k.polarInertia))
           < square(tau);
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
    BondLoad load;

    const Vec3 separation = b.position - a.position;
    const double length = separation.norm();
    const Vec3 n = separation * (1.0 / length);
    load.length = length;
    load.direction = n;

    // Lever arms split the actual distance in the ratio of the radii, so that
    // the shear force's torques balance its moment and angular momentum is exact.
    const double armA = length * k.armFractionA;
    const double armB = length - armA;
    load.centre = a.position + armA * n;

    const Vec3 contactVelocityA = a.velocity + a.angularVelocity.cross(armA * n);
    const Vec3 contactVelocityB = b.velocity + b.angularVelocity.cross(-armB * n);
    const Vec3 relativeVelocity = contactVelocityB - contactVelocityA;
    const double normalVelocity = relativeVelocity.dot(n);
    const Vec3 tangentialVelocity = relativeVelocity - normalVelocity * n;

    const Vec3 relativeSpin = b.angularVelocity - a.angularVelocity;
    const double twistRate = relativeSpin.dot(n);
    const Vec3 bendingRate = relativeSpin - twistRate * n;

    state.shearDisplacement = rotateIntoTangentPlane(state.shearDisplacement, n) + tangentialVelocity * dt;
    state.twistAngle += twistRate * dt;
    state.bendingAngle = rotateIntoTangentPlane(state.bendingAngle, n) + bendingRate * dt;

    // Spring loads, acting on b.
    double normalForce = k.normal * (length - state.restLength);   // tension positive
    Vec3 shearForce = -k.shear * state.shearDisplacement;
    const Vec3 twistTorque = -k.twist * state.twistAngle * n;
    const Vec3 bendingTorque = -k.bending * state.bendingAngle;

    const double shear2 = shearForce.squaredNorm();
    const double twist2 = twistTorque.squaredNorm();
    const double bending2 = bendingTorque.squaredNorm();
    if (!family_.unbreakable && !surelyIntact(state, k, normalForce, shear2, twist2, bending2))
    {
        load.broke = breakage(state, k, normalForce, std::sqrt(shear2), std::sqrt(twist2), std::sqrt(bending2));
        if (load.broke != BreakMode::none)
        {
            return load;
        }
    }

    if (damping_.model == DampingModel::viscous && damping_.dampingRatio > 0.0)
    {
        const double reducedMass = a.mass * b.mass / (a.mass + b.mass);
        normalForce += 2.0 * damping_.dampingRatio * std::sqrt(reducedMass * k.normal) * normalVelocity;
        shearForce -= 2.0 * damping_.dampingRatio * std::sqrt(reducedMass * k.shear) * tangentialVelocity;
    }

    const Vec3 forceOnB = -normalForce * n + shearForce;
    load.normalForce = normalForce;
    load.forceOnA = -forceOnB;
    load.torqueOnA = (armA * n).cross(-shearForce) - twistTorque - bendingTorque;
    load.torqueOnB = (-armB * n).cross(shearForce) + twistTorque + bendingTorque;
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
        k.normal * stretch * stretch
      + k.shear * state.shearDisplacement.squaredNorm()
      + k.twist * state.twistAngle * state.twistAngle
      + k.bending * state.bendingAngle.squaredNorm()
    );
}

} // namespace iceDEM
