#include "TimeStep.H"

#include "BondModel.H"
#include "InputError.H"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

TimeStepLimits timeStepLimits
(
    const IceProperties& props,
    double minRadius,
    int maxNeighbours,
    double inertiaScaling
)
{
    TimeStepLimits limits;
    if (!(inertiaScaling >= 1.0))
    {
        throw std::invalid_argument("timeStepLimits: inertiaScaling must be >= 1");
    }
    limits.inertiaScaling = inertiaScaling;
    // The density the equations of motion see (inertia scaling), not the weight's.
    const double rho = inertiaScaling * props.material.density;
    const double mass = rho * 4.0 / 3.0 * M_PI * std::pow(minRadius, 3);
    const double rotationalInertia = 0.4 * mass * minRadius * minRadius;

    double maxModulus = props.material.youngsModulus;
    limits.stiffestSpring = HUGE_VAL;
    auto consider = [&](const std::string& name, double inertia, double stiffness)
    {
        const double step = 2.0 * std::sqrt(inertia / stiffness);
        if (step < limits.stiffestSpring)
        {
            limits.stiffestSpring = step;
            limits.stiffestSpringName = name;
        }
    };

    // Contact: K_n = pi E D / 4, K_t = K_n / (2 (1 + nu)).
    const double contactNormal = M_PI * props.material.youngsModulus * 2.0 * minRadius / 4.0;
    consider("contact normal", mass, contactNormal);

    for (int f = 0; f < nBondFamilies; ++f)
    {
        const BondFamilyParameters& family = props.families[f];
        const BondStiffness k = BondStiffness::of(family, minRadius, minRadius);
        const std::string name = toString(static_cast<BondFamily>(f)) + " bond ";
        consider(name + "normal", mass, std::max(k.normal, k.normalCompression));
        consider(name + "shear", mass, k.shear);
        // The shear spring also turns the particle through its lever arm.
        consider(name + "shear (rotation)", rotationalInertia, k.shear * minRadius * minRadius);
        consider(name + "twist", rotationalInertia, k.twist);
        consider(name + "bending", rotationalInertia, k.bending);
        maxModulus = std::max({maxModulus, family.youngsModulus, family.compressionModulusOrYoungs()});
    }

    limits.recommended = props.timeStep.factor * 2.0 * minRadius * std::sqrt(rho / maxModulus);
    limits.maxNeighbours = std::max(1, maxNeighbours);
    limits.limit = limits.stiffestSpring / std::sqrt(2.0 * limits.maxNeighbours);
    return limits;
}


double chooseTimeStep
(
    const IceProperties& props,
    const TimeStepLimits& limits,
    const std::string& dictPath
)
{
    const bool fixed = props.timeStep.deltaT > 0.0;
    const double dt = fixed ? props.timeStep.deltaT : limits.recommended;
    if (dt > limits.limit && !props.timeStep.refuseUnsafe)
    {
        std::cerr << "warning: " << dictPath << ": time step " << dt << " s is above the program's limit "
                  << limits.limit << " s (" << limits.stiffestSpringName << "); it runs because "
                  << "timeStep.refuseUnsafe is no (stability studies only)" << std::endl;
    }
    else if (dt > limits.limit)
    {
        std::ostringstream msg;
        msg << "time step " << dt << " s is unsafe: the stiffest spring ("
            << limits.stiffestSpringName << ") has a critical step of "
            << limits.stiffestSpring << " s, and with up to " << limits.maxNeighbours
            << " bonds/contacts on one particle the program accepts at most "
            << limits.limit << " s (factor "
            << limits.limit / limits.recommended * props.timeStep.factor << ")";
        if (limits.inertiaScaling != 1.0)
        {
            msg << " with the inertia scaled by " << limits.inertiaScaling;
        }
        msg << ". Lower " << (fixed ? "timeStep.deltaT" : "timeStep.factor") << ".";
        throw InputError(dictPath, fixed ? "timeStep.deltaT" : "timeStep.factor", msg.str());
    }
    return dt;
}

} // namespace iceDEM
