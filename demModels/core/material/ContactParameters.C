#include "ContactParameters.H"

#include <cmath>

namespace iceDEM
{

ContactParameters ContactParameters::of(const IceProperties& ice, double meanDiameter, double minMass)
{
    ContactParameters c;
    c.normalStiffness = M_PI*ice.material.youngsModulus*meanDiameter/4.0;
    c.tangentialStiffness = c.normalStiffness/(2.0*(1.0 + ice.material.poissonsRatio));
    if (ice.damping.model == DampingModel::viscous)
    {
        const double reducedMass = 0.5*minMass;
        c.normalDamping = 2.0*ice.damping.dampingRatio*std::sqrt(reducedMass*c.normalStiffness);
        c.tangentialDamping = 2.0*ice.damping.dampingRatio*std::sqrt(reducedMass*c.tangentialStiffness);
    }
    c.friction = ice.material.frictionCoefficient;
    c.rollingFriction = ice.material.rollingFrictionCoefficient;
    return c;
}

} // namespace iceDEM
