#include "BondModel.H"

#include <cmath>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

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
    BondState* states[] = {&state};
    const BondStiffness* stiffnesses[] = {&k};
    const ParticleState* as[] = {&a};
    const ParticleState* bs[] = {&b};
    BondLoad load;
    evaluateLanes<1>(1, states, stiffnesses, as, bs, dt, &load);
    return load;
}


namespace
{

// One number per bond of a batch, and the vector operations of the bond
// model on them, written out in the order Eigen evaluates them for one bond.
template<int lanes>
struct Lanes
{
    double v[lanes];
};

template<int lanes>
struct Lanes3
{
    Lanes<lanes> x, y, z;
};

template<int lanes, class Op>
inline Lanes<lanes> each(const Lanes<lanes>& p, const Lanes<lanes>& q, Op op)
{
    Lanes<lanes> r;
    for (int l = 0; l < lanes; ++l) r.v[l] = op(p.v[l], q.v[l]);
    return r;
}

template<int lanes>
inline Lanes<lanes> operator+(const Lanes<lanes>& p, const Lanes<lanes>& q) { return each(p, q, [](double x, double y) { return x + y; }); }
template<int lanes>
inline Lanes<lanes> operator-(const Lanes<lanes>& p, const Lanes<lanes>& q) { return each(p, q, [](double x, double y) { return x - y; }); }
template<int lanes>
inline Lanes<lanes> operator*(const Lanes<lanes>& p, const Lanes<lanes>& q) { return each(p, q, [](double x, double y) { return x * y; }); }
template<int lanes>
inline Lanes<lanes> operator/(const Lanes<lanes>& p, const Lanes<lanes>& q) { return each(p, q, [](double x, double y) { return x / y; }); }

template<int lanes>
inline Lanes<lanes> operator-(const Lanes<lanes>& p)
{
    Lanes<lanes> r;
    for (int l = 0; l < lanes; ++l) r.v[l] = -p.v[l];
    return r;
}

template<int lanes>
inline Lanes<lanes> squareRoot(const Lanes<lanes>& p)
{
    Lanes<lanes> r;
    int l = 0;
#ifdef __SSE2__
    // Two lanes per instruction, same bits: std::sqrt would keep the compiler
    // from pairing them, as it must set errno for a negative argument.
    for (; l + 2 <= lanes; l += 2)
    {
        _mm_storeu_pd(r.v + l, _mm_sqrt_pd(_mm_loadu_pd(p.v + l)));
    }
#endif
    for (; l < lanes; ++l)
    {
        r.v[l] = std::sqrt(p.v[l]);
    }
    return r;
}

template<int lanes>
inline Lanes3<lanes> operator+(const Lanes3<lanes>& p, const Lanes3<lanes>& q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
template<int lanes>
inline Lanes3<lanes> operator-(const Lanes3<lanes>& p, const Lanes3<lanes>& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
template<int lanes>
inline Lanes3<lanes> operator-(const Lanes3<lanes>& p) { return {-p.x, -p.y, -p.z}; }
template<int lanes>
inline Lanes3<lanes> operator*(const Lanes<lanes>& s, const Lanes3<lanes>& p) { return {s * p.x, s * p.y, s * p.z}; }
template<int lanes>
inline Lanes3<lanes> operator*(const Lanes3<lanes>& p, const Lanes<lanes>& s) { return {p.x * s, p.y * s, p.z * s}; }
template<int lanes>
inline Lanes<lanes> dot(const Lanes3<lanes>& p, const Lanes3<lanes>& q) { return p.x * q.x + p.y * q.y + p.z * q.z; }
template<int lanes>
inline Lanes<lanes> squaredNorm(const Lanes3<lanes>& p) { return dot(p, p); }

template<int lanes>
inline Lanes3<lanes> cross(const Lanes3<lanes>& p, const Lanes3<lanes>& q)
{
    return {p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x};
}

template<int lanes>
inline Lanes<lanes> broadcast(double s)
{
    Lanes<lanes> r;
    for (int l = 0; l < lanes; ++l) r.v[l] = s;
    return r;
}

template<int lanes>
inline void set(Lanes3<lanes>& p, int l, const Vec3& v)
{
    p.x.v[l] = v.x();
    p.y.v[l] = v.y();
    p.z.v[l] = v.z();
}

template<int lanes>
inline Vec3 get(const Lanes3<lanes>& p, int l)
{
    return Vec3(p.x.v[l], p.y.v[l], p.z.v[l]);
}

//- rotateIntoTangentPlane on every lane.
template<int lanes>
inline Lanes3<lanes> rotateEachIntoTangentPlane(const Lanes3<lanes>& stored, const Lanes3<lanes>& n)
{
    const Lanes<lanes> length = squareRoot(squaredNorm(stored));
    const Lanes3<lanes> projected = stored - dot(stored, n) * n;
    const Lanes<lanes> projectedLength = squareRoot(squaredNorm(projected));
    Lanes3<lanes> rotated = projected * (length / projectedLength);
    for (int l = 0; l < lanes; ++l)
    {
        if (projectedLength.v[l] <= 1e-300)
        {
            rotated.x.v[l] = rotated.y.v[l] = rotated.z.v[l] = 0.0;
        }
    }
    return rotated;
}

} // namespace


Vec3 rotateIntoTangentPlane(const Vec3& stored, const Vec3& n)
{
    Lanes3<1> s, d;
    set(s, 0, stored);
    set(d, 0, n);
    return get(rotateEachIntoTangentPlane(s, d), 0);
}


template<int lanes>
void BondModel::evaluateLanes
(
    int count,
    BondState* const states[],
    const BondStiffness* const stiffnesses[],
    const ParticleState* const a[],
    const ParticleState* const b[],
    double dt,
    BondLoad loads[]
) const
{
    // Unused lanes repeat the first bond; their results are dropped.
    Lanes3<lanes> positionA, positionB, velocityA, velocityB, spinA, spinB, shearDisplacement, bendingAngle;
    Lanes<lanes> radiusA, radiusB, restLength, twistAngle, kNormal, kShear, kTwist, kBending;
    for (int l = 0; l < lanes; ++l)
    {
        const int bond = l < count ? l : 0;
        const ParticleState& pa = *a[bond];
        const ParticleState& pb = *b[bond];
        const BondState& s = *states[bond];
        const BondStiffness& k = *stiffnesses[bond];
        set(positionA, l, pa.position);
        set(positionB, l, pb.position);
        set(velocityA, l, pa.velocity);
        set(velocityB, l, pb.velocity);
        set(spinA, l, pa.angularVelocity);
        set(spinB, l, pb.angularVelocity);
        set(shearDisplacement, l, s.shearDisplacement);
        set(bendingAngle, l, s.bendingAngle);
        restLength.v[l] = s.restLength;
        twistAngle.v[l] = s.twistAngle;
        radiusA.v[l] = pa.radius;
        radiusB.v[l] = pb.radius;
        kNormal.v[l] = k.normal;
        kShear.v[l] = k.shear;
        kTwist.v[l] = k.twist;
        kBending.v[l] = k.bending;
    }
    const Lanes<lanes> step = broadcast<lanes>(dt);

    const Lanes3<lanes> separation = positionB - positionA;
    const Lanes<lanes> length = squareRoot(squaredNorm(separation));
    const Lanes3<lanes> n = {separation.x / length, separation.y / length, separation.z / length};

    // Lever arms split the actual distance in the ratio of the radii, so that
    // the shear force's torques balance its moment and angular momentum is exact.
    const Lanes<lanes> armA = length * radiusA / (radiusA + radiusB);
    const Lanes<lanes> armB = length - armA;
    const Lanes3<lanes> centre = positionA + armA * n;

    const Lanes3<lanes> contactVelocityA = velocityA + cross(spinA, armA * n);
    const Lanes3<lanes> contactVelocityB = velocityB + cross(spinB, -armB * n);
    const Lanes3<lanes> relativeVelocity = contactVelocityB - contactVelocityA;
    const Lanes<lanes> normalVelocity = dot(relativeVelocity, n);
    const Lanes3<lanes> tangentialVelocity = relativeVelocity - normalVelocity * n;

    const Lanes3<lanes> relativeSpin = spinB - spinA;
    const Lanes<lanes> twistRate = dot(relativeSpin, n);
    const Lanes3<lanes> bendingRate = relativeSpin - twistRate * n;

    shearDisplacement = rotateEachIntoTangentPlane(shearDisplacement, n) + tangentialVelocity * step;
    twistAngle = twistAngle + twistRate * step;
    bendingAngle = rotateEachIntoTangentPlane(bendingAngle, n) + bendingRate * step;

    // Spring loads, acting on b.
    const Lanes<lanes> springNormalForce = kNormal * (length - restLength);   // tension positive
    Lanes<lanes> normalForce = springNormalForce;
    Lanes3<lanes> shearForce = -kShear * shearDisplacement;
    const Lanes3<lanes> twistTorque = (-kTwist * twistAngle) * n;
    const Lanes3<lanes> bendingTorque = -kBending * bendingAngle;
    const Lanes<lanes> shear2 = squaredNorm(shearForce);
    const Lanes<lanes> twist2 = squaredNorm(twistTorque);
    const Lanes<lanes> bending2 = squaredNorm(bendingTorque);

    if (damping_.model == DampingModel::viscous && damping_.dampingRatio > 0.0)
    {
        Lanes<lanes> reducedMass;
        for (int l = 0; l < lanes; ++l)
        {
            const int bond = l < count ? l : 0;
            reducedMass.v[l] = a[bond]->mass * b[bond]->mass / (a[bond]->mass + b[bond]->mass);
        }
        const Lanes<lanes> ratio2 = broadcast<lanes>(2.0 * damping_.dampingRatio);
        normalForce = normalForce + ratio2 * squareRoot(reducedMass * kNormal) * normalVelocity;
        shearForce = shearForce - (ratio2 * squareRoot(reducedMass * kShear)) * tangentialVelocity;
    }

    const Lanes3<lanes> forceOnB = -normalForce * n + shearForce;
    const Lanes3<lanes> torqueOnA = cross(armA * n, -shearForce) - twistTorque - bendingTorque;
    const Lanes3<lanes> torqueOnB = cross(-armB * n, shearForce) + twistTorque + bendingTorque;

    for (int l = 0; l < count; ++l)
    {
        BondState& s = *states[l];
        s.shearDisplacement = get(shearDisplacement, l);
        s.twistAngle = twistAngle.v[l];
        s.bendingAngle = get(bendingAngle, l);

        BondLoad& load = loads[l];
        load.centre = get(centre, l);
        load.length = length.v[l];
        load.direction = get(n, l);
        // The limits apply to the spring loads, before any viscous damping.
        load.broke = breakMode(s, *stiffnesses[l], springNormalForce.v[l], shear2.v[l], twist2.v[l], bending2.v[l]);
        if (load.broke != BreakMode::none)
        {
            load.normalForce = 0.0;
            load.forceOnA = load.torqueOnA = load.torqueOnB = Vec3::Zero();
            continue;
        }
        load.normalForce = normalForce.v[l];
        load.forceOnA = -get(forceOnB, l);
        load.torqueOnA = get(torqueOnA, l);
        load.torqueOnB = get(torqueOnB, l);
    }
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
