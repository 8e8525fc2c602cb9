#include "Format.H"

#include <algorithm>
#include <charconv>
#include <iomanip>
#include <sstream>

namespace iceDEM
{

namespace
{
std::string withDigits(double v, int digits)
{
    std::ostringstream s;
    s << std::setprecision(digits) << v;
    return s.str();
}
}


std::string formatNumber(double v)
{
    return withDigits(v, 10);
}


std::string exactNumber(double v)
{
    return withDigits(v, 17);
}


std::string shortestNumber(double v)
{
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, v);
    return std::string(text, result.ptr);
}


std::string formatDuration(double seconds)
{
    std::ostringstream s;
    const long total = static_cast<long>(std::max(0.0, seconds));
    if (total >= 3600) s << total / 3600 << " h ";
    if (total >= 60) s << (total % 3600) / 60 << " min ";
    s << total % 60 << " s";
    return s.str();
}

} // namespace iceDEM
