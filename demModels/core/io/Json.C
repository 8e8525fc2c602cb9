#include "Json.H"

namespace iceDEM
{

std::string jsonText(const Json& j)
{
    return j.dump(2) + "\n";
}

} // namespace iceDEM
