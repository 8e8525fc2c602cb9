#include "couplingInterval.H"
#include "error.H"

namespace Foam
{
namespace iceCoupling
{

couplingInterval::couplingInterval
(
    const dictionary& couplingProperties,
    scalar demTimeStep,
    scalar fluidTimeStep
)
:
    demTimeStep_(demTimeStep),
    demSteps_(couplingProperties.get<label>("couplingInterval")),
    fluidSteps_(0)
{
    if (demSteps_ < 1)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'couplingInterval' is " << demSteps_
            << ": it is the number of DEM steps per coupling step, a whole number >= 1"
            << exit(FatalIOError);
    }
    const scalar ratio = time()/fluidTimeStep;
    fluidSteps_ = label(std::round(ratio));
    if (fluidSteps_ < 1 || mag(ratio - fluidSteps_) > 1e-9*ratio)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'couplingInterval': " << demSteps_ << " DEM steps of " << demTimeStep
            << " s make a coupling time of " << time() << " s, which the fluid time step"
            << " deltaT = " << fluidTimeStep << " s (system/controlDict) does not divide"
            << " (ratio " << ratio << "). The fluid must advance the coupling time in a whole"
            << " number of steps: set deltaT to the coupling time divided by a whole number,"
            << " or change couplingInterval" << exit(FatalIOError);
    }
}

} // namespace iceCoupling
} // namespace Foam
