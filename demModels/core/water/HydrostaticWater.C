#include "HydrostaticWater.H"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace iceDEM
{

double submergedSphereVolume(double radius, double depth)
{
    const double h = std::clamp(depth, 0.0, 2.0 * radius);
    return M_PI * h * h * (3.0 * radius - h) / 3.0;
}


HydrostaticWater::HydrostaticWater(const HydrostaticWaterParameters& p)
:
    p_(p)
{}


Vec3 HydrostaticWater::submergedSphereDrag(double radius, const Vec3& velocity) const
{
    const double speed = velocity.norm();
    if (!p_.drag || speed == 0.0)
    {
        return Vec3::Zero();
    }
    const double reynolds = p_.density * speed * 2.0 * radius / p_.viscosity;
    const double area = M_PI * radius * radius;
    return -0.5 * p_.density * schillerNaumannDragCoefficient(reynolds) * area * speed * velocity;
}


SphereWaterLoad HydrostaticWater::sphereLoad(double radius, double z, const Vec3& velocity) const
{
    SphereWaterLoad load;
    load.submergedVolume = submergedSphereVolume(radius, p_.surfaceLevel - (z - radius));
    if (load.submergedVolume == 0.0)
    {
        return load;
    }
    const double volume = 4.0 / 3.0 * M_PI * radius * radius * radius;
    load.buoyancy = Vec3(0.0, 0.0, buoyancy(load.submergedVolume));
    load.drag = load.submergedVolume / volume * submergedSphereDrag(radius, velocity);
    load.addedMass = p_.addedMassCoefficient * p_.density * load.submergedVolume;
    return load;
}


double HydrostaticWater::buoyancy(double submergedVolume) const
{
    return p_.density * p_.gravity * submergedVolume;
}


double HydrostaticWater::submergedPrismVolume(double planArea, double zBottom, double zTop) const
{
    return planArea * std::clamp(p_.surfaceLevel - zBottom, 0.0, std::max(0.0, zTop - zBottom));
}


double HydrostaticWater::submergedHorizontalCylinderVolume(double radius, double length, double zAxis) const
{
    // Circular segment below the surface, of height h measured from the bottom.
    const double h = std::clamp(p_.surfaceLevel - (zAxis - radius), 0.0, 2.0 * radius);
    // r^2 alpha - c s with half-angle alpha: atan2 keeps it accurate near empty and full.
    const double c = radius - h;
    const double s = std::sqrt(h * (2.0 * radius - h));
    const double segment = radius * radius * std::atan2(s, c) - c * s;
    return segment * length;
}


namespace
{

//- Root of f on [lo, hi] (f(lo), f(hi) of opposite signs) to machine precision.
template<class F>
double bisect(F f, double lo, double hi)
{
    double flo = f(lo);
    for (int k = 0; k < 200 && hi - lo > 0.0; ++k)
    {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi)
        {
            break;
        }
        const double fmid = f(mid);
        if ((fmid < 0.0) == (flo < 0.0))
        {
            lo = mid;
            flo = fmid;
        }
        else
        {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

} // namespace


double terminalVelocity(const HydrostaticWater& water, double radius, double particleDensity)
{
    const HydrostaticWaterParameters& p = water.parameters();
    const double volume = 4.0 / 3.0 * M_PI * radius * radius * radius;
    const double netWeight = (particleDensity - p.density) * p.gravity * volume;   // > 0: sinks
    const double magnitude = std::abs(netWeight);
    auto dragMinusWeight = [&](double speed)
    {
        return water.submergedSphereDrag(radius, Vec3(0.0, 0.0, speed)).norm() - magnitude;
    };
    // Drag grows without bound with speed: double until it exceeds the weight.
    double hi = 1e-6;
    while (dragMinusWeight(hi) < 0.0)
    {
        hi *= 2.0;
    }
    const double speed = bisect(dragMinusWeight, 0.0, hi);
    return netWeight > 0.0 ? -speed : speed;
}


double floatingSphereDraft(double radius, double particleDensity, double waterDensity)
{
    if (!(particleDensity > 0.0 && particleDensity < waterDensity))
    {
        throw std::invalid_argument("a sphere floats only if it is lighter than the water");
    }
    const double mass = particleDensity * 4.0 / 3.0 * M_PI * radius * radius * radius;
    return bisect
    (
        [&](double h) { return waterDensity * submergedSphereVolume(radius, h) - mass; },
        0.0,
        2.0 * radius
    );
}



double levelDraft(const std::vector<ParticleSpec>& spheres, double densityRatio)
{
    if (spheres.empty() || !(densityRatio > 0.0 && densityRatio < 1.0))
    {
        throw std::invalid_argument("levelDraft needs spheres and a density ratio in (0, 1)");
    }
    double bottom = HUGE_VAL, top = -HUGE_VAL, volume = 0.0;
    for (const ParticleSpec& p : spheres)
    {
        bottom = std::min(bottom, p.position.z() - p.radius);
        top = std::max(top, p.position.z() + p.radius);
        volume += 4.0 / 3.0 * M_PI * p.radius * p.radius * p.radius;
    }
    auto excess = [&](double draft)
    {
        double submerged = 0.0;
        for (const ParticleSpec& p : spheres)
        {
            submerged += submergedSphereVolume(p.radius, draft - (p.position.z() - p.radius - bottom));
        }
        return submerged - densityRatio * volume;
    };
    return bisect(excess, 0.0, top - bottom);
}

} // namespace iceDEM
