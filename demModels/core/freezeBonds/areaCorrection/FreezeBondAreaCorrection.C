#include "FreezeBondAreaCorrection.H"

#include "Dictionary.H"
#include "GivenAreaCorrection.H"
#include "HeatBalanceAreaCorrection.H"
#include "InterfaceAreaCorrection.H"
#include "SelectionTable.H"

#include <cmath>
#include <stdexcept>

namespace iceDEM
{

namespace
{

using AreaCorrections = SelectionTable<FreezeBondAreaCorrection, const Dictionary&>;

const AreaCorrections areaCorrections
{{
    {"given", &AreaCorrections::construct<GivenAreaCorrection>},
    {"heatBalance", &AreaCorrections::construct<HeatBalanceAreaCorrection>},
    {"interface", &AreaCorrections::construct<InterfaceAreaCorrection>},
}};

} // namespace


std::unique_ptr<FreezeBondAreaCorrection> FreezeBondAreaCorrection::New(const Dictionary& a)
{
    return areaCorrections.New(a, "model", a);
}


const std::vector<std::string>& FreezeBondAreaCorrection::names()
{
    return areaCorrections.names();
}


void FreezeBondAreaCorrection::setValue(double cf)
{
    if (!(cf > 0.0) || !std::isfinite(cf))
    {
        throw std::invalid_argument("FreezeBondAreaCorrection::setValue: c_f must be positive");
    }
    value_ = cf;
}

} // namespace iceDEM
