#include "IceTypes.H"

namespace iceDEM
{

std::string toString(BondFamily f)
{
    switch (f)
    {
        case BondFamily::ice: return "ice";
        case BondFamily::freeze: return "freeze";
    }
    return "unknown";
}


std::string toString(BreakMode m)
{
    switch (m)
    {
        case BreakMode::none: return "none";
        case BreakMode::tension: return "tension";
        case BreakMode::shear: return "shear";
        case BreakMode::twist: return "twist";
        case BreakMode::bending: return "bending";
    }
    return "unknown";
}


std::string toString(StrengthModel m)
{
    switch (m)
    {
        case StrengthModel::stress: return "stress";
        case StrengthModel::strain: return "strain";
        case StrengthModel::perBond: return "freezeBondProperties";
    }
    return "unknown";
}


std::string toString(BreakageCriterion c)
{
    switch (c)
    {
        case BreakageCriterion::separate: return "separate";
        case BreakageCriterion::combined: return "combined";
    }
    return "unknown";
}


std::string toString(DampingModel m)
{
    switch (m)
    {
        case DampingModel::none: return "none";
        case DampingModel::hysteretic: return "hysteretic";
        case DampingModel::viscous: return "viscous";
    }
    return "unknown";
}

} // namespace iceDEM
