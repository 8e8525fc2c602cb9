#include "HeatBalanceAreaCorrection.H"

#include "Dictionary.H"

#include <cmath>

namespace iceDEM
{

HeatBalanceAreaCorrection::HeatBalanceAreaCorrection(const Dictionary& a)
:
    FreezeBondAreaCorrection(1.0)
{
    a.checkKeys({"model", "heatCapacity", "temperatureDrop", "latentHeat", "contactLength",
                 "bandWidthPerGrowth", "bondsPerContact"});
    auto positive = [&](const std::string& key, double def)
    {
        const double v = a.getScalarOrDefault(key, def);
        if (!(v > 0.0)) a.fail(key, "must be positive");
        return v;
    };
    heatCapacity_ = positive("heatCapacity", heatCapacity_);
    temperatureDrop_ = positive("temperatureDrop", temperatureDrop_);
    latentHeat_ = positive("latentHeat", latentHeat_);
    contactLength_ = positive("contactLength", contactLength_);
    bandWidthPerGrowth_ = positive("bandWidthPerGrowth", bandWidthPerGrowth_);
    bondsPerContact_ = a.getLabelOrDefault("bondsPerContact", bondsPerContact_);
    if (bondsPerContact_ < 1) a.fail("bondsPerContact", "must be at least 1");
}


double HeatBalanceAreaCorrection::forBlocks
(
    double blockVolume,
    double blockSurface,
    double bondRadius
) const
{
    const double fraction = newIceFraction(heatCapacity_, temperatureDrop_, latentHeat_);
    const double growth = iceGrowth(fraction, blockVolume, blockSurface);
    return fromBand(bandWidthPerGrowth_*growth, contactLength_, bondsPerContact_, bondRadius);
}


double HeatBalanceAreaCorrection::newIceFraction(double heatCapacity, double temperatureDrop, double latentHeat)
{
    return heatCapacity*temperatureDrop/latentHeat;
}


double HeatBalanceAreaCorrection::iceGrowth(double fraction, double blockVolume, double blockSurface)
{
    return fraction*blockVolume/blockSurface;
}


double HeatBalanceAreaCorrection::fromBand
(
    double bandWidth,
    double contactLength,
    int bondsPerContact,
    double bondRadius
)
{
    return bandWidth*contactLength/(bondsPerContact*M_PI*bondRadius*bondRadius);
}

} // namespace iceDEM
