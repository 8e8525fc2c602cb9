#include "InertiaScaling.H"

#include "Dictionary.H"
#include "Format.H"

#include <cmath>

namespace iceDEM
{

double readInertiaScaling(const Dictionary& d, const std::string& key)
{
    if (!d.found(key))
    {
        return 1.0;
    }
    const double s = d.getScalar(key);
    if (!(s >= 1.0 && s <= maxInertiaScaling))
    {
        d.fail(key, formatNumber(s) + " is not allowed; expected a number in [1, " + formatNumber(maxInertiaScaling)
            + "] (1: the true inertia; s > 1 multiplies mass and moment of inertia in the equations of motion by s)");
    }
    return s;
}


void refuseInertiaScaling(const Dictionary& d, const std::string& key, const std::string& why)
{
    if (!d.found(key))
    {
        return;
    }
    const double s = d.getScalar(key);
    if (s != 1.0)
    {
        d.fail(key, formatNumber(s) + " is not allowed here (only 1): " + why);
    }
}


double readMaxKineticToWorkRatio(const Dictionary& control)
{
    return control.getPositiveScalarOrDefault("maxKineticToWorkRatio", defaultMaxKineticToWorkRatio);
}

} // namespace iceDEM
