#include "ClampedEnds.H"

namespace iceDEM
{

ClampedEnds::ClampedEnds(const Dictionary& d)
:
    EndSupport(d, "clamped")
{}


std::string ClampedEnds::description() const
{
    return "clamped: the end pads neither move nor rotate";
}

} // namespace iceDEM
