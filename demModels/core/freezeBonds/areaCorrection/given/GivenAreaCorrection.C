#include "GivenAreaCorrection.H"

#include "Dictionary.H"

namespace iceDEM
{

GivenAreaCorrection::GivenAreaCorrection(const Dictionary& a)
:
    FreezeBondAreaCorrection(1.0)
{
    a.checkKeys({"model", "value"});
    const double cf = a.getScalar("value");
    if (!(cf > 0.0))
    {
        a.fail("value", "c_f must be positive");
    }
    setValue(cf);
}

} // namespace iceDEM
