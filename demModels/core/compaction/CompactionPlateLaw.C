#include "CompactionPlateLaw.H"

#include <algorithm>

namespace iceDEM
{

double CompactionPlateLaw::force
(
    double z, double vz, double r,
    double bottom, double top,
    double bottomVelocity, double topVelocity
) const
{
    double f = 0.0;
    const double intoFloor = bottom - (z - r);
    if (intoFloor > 0.0)
    {
        f += std::max(0.0, normalStiffness*intoFloor - normalDamping*(vz - bottomVelocity));
    }
    const double intoLid = (z + r) - top;
    if (intoLid > 0.0)
    {
        f -= std::max(0.0, normalStiffness*intoLid + normalDamping*(vz - topVelocity));
    }
    return f;
}


double gapForPorosity(double iceVolume, double planArea, double porosity)
{
    return iceVolume/(planArea*(1.0 - porosity));
}


double porosityInGap(double iceVolume, double planArea, double gap)
{
    return 1.0 - iceVolume/(planArea*gap);
}

} // namespace iceDEM
