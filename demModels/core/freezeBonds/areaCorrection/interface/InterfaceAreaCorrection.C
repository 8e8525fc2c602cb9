#include "InterfaceAreaCorrection.H"

#include "Dictionary.H"

namespace iceDEM
{

InterfaceAreaCorrection::InterfaceAreaCorrection(const Dictionary& a)
:
    FreezeBondAreaCorrection(1.0)
{
    a.checkKeys({"model"});
}

} // namespace iceDEM
