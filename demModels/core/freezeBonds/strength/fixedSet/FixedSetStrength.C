#include "FixedSetStrength.H"

#include "Dictionary.H"

#include <sstream>
#include <stdexcept>

namespace iceDEM
{

FixedSetStrength::FixedSetStrength(const Dictionary& d)
:
    FreezeBondStrengthModel(d.fileName())
{
    const Dictionary& c = d.subDict("fixedSetCoeffs");
    c.checkKeys({"set", "sets"});
    const Dictionary& sets = c.subDict("sets");
    setName_ = c.getWord("set");
    if (!sets.isDict(setName_))
    {
        std::string allowed;
        for (const std::string& k : sets.keys()) allowed += " " + k;
        c.fail("set", "unknown set '" + setName_ + "'; defined in sets:" + allowed);
    }
    const Dictionary& s = sets.subDict(setName_);
    s.checkKeys({"tensile", "shear"});
    tensile_ = s.getScalar("tensile");
    shear_ = s.getScalar("shear");
    if (!(tensile_ > 0.0)) s.fail("tensile", "must be positive (Pa)");
    if (!(shear_ > 0.0)) s.fail("shear", "must be positive (Pa)");
}


double FixedSetStrength::tensile(double) const
{
    return tensile_;
}


double FixedSetStrength::shear(double) const
{
    return shear_;
}


void FixedSetStrength::setStrengths(double tensile, double shear)
{
    if (!(tensile > 0.0 && shear > 0.0))
    {
        throw std::invalid_argument("FixedSetStrength::setStrengths: strengths must be positive");
    }
    tensile_ = tensile;
    shear_ = shear;
}


std::string FixedSetStrength::summary() const
{
    std::ostringstream out;
    out << "freeze-bond set " << setName_ << ": tensile " << tensile_*1e-3 << " kPa, shear " << shear_*1e-3 << " kPa";
    return out.str();
}

} // namespace iceDEM
