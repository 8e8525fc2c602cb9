#include "IceTypes.H"

namespace iceDEM
{

// "unknown" for a code outside the enum (read back from a file).
std::string toString(BondFamily f) { return bondFamilyNames.nameOr(f, "unknown"); }
std::string toString(BreakMode m) { return breakModeNames.nameOr(m, "unknown"); }
std::string toString(StrengthModel m) { return strengthModelNames.nameOr(m, "unknown"); }
std::string toString(BreakageCriterion c) { return breakageCriterionNames.nameOr(c, "unknown"); }
std::string toString(DampingModel m) { return dampingModelNames.nameOr(m, "unknown"); }

} // namespace iceDEM
