#include "FreezeBondStrengthModel.H"

#include "ConfinementLineStrength.H"
#include "Dictionary.H"
#include "FixedSetStrength.H"
#include "InputError.H"
#include "SelectionTable.H"

namespace iceDEM
{

namespace
{

using StrengthModels = SelectionTable<FreezeBondStrengthModel, const Dictionary&>;

const StrengthModels strengthModels
{{
    {"confinementLine", &StrengthModels::construct<ConfinementLineStrength>},
    {"fixedSet", &StrengthModels::construct<FixedSetStrength>},
}};

} // namespace


std::unique_ptr<FreezeBondStrengthModel> FreezeBondStrengthModel::New(const Dictionary& d)
{
    return strengthModels.New(d, "strengthModel", d);
}


const std::vector<std::string>& FreezeBondStrengthModel::names()
{
    return strengthModels.names();
}


void FreezeBondStrengthModel::setSubmersionTime(double minutes)
{
    if (!(minutes > 0.0))
    {
        throw InputError(fileName_, "submersionTime", "must be positive (minutes)");
    }
    submersionTime_ = minutes;
    atSubmersionTime(minutes);
}

} // namespace iceDEM
