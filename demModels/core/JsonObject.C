#include "JsonObject.H"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace iceDEM
{

std::string jsonNumber(double v)
{
    if (!std::isfinite(v))
    {
        return "null";
    }
    std::ostringstream s;
    s << std::setprecision(10) << v;
    return s.str();
}


namespace
{
std::string quoted(const std::string& s)
{
    std::string out = "\"";
    for (char c : s)
    {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') { out += "\\n"; continue; }
        out += c;
    }
    return out + "\"";
}
}


JsonObject& JsonObject::add(const std::string& key, double value)
{
    members_.push_back({key, jsonNumber(value), nullptr});
    return *this;
}


JsonObject& JsonObject::add(const std::string& key, long value)
{
    members_.push_back({key, std::to_string(value), nullptr});
    return *this;
}


JsonObject& JsonObject::add(const std::string& key, bool value)
{
    members_.push_back({key, value ? "true" : "false", nullptr});
    return *this;
}


JsonObject& JsonObject::add(const std::string& key, const std::string& value)
{
    members_.push_back({key, quoted(value), nullptr});
    return *this;
}


JsonObject& JsonObject::add(const std::string& key, const std::vector<double>& values)
{
    std::string list = "[";
    for (std::size_t k = 0; k < values.size(); ++k)
    {
        list += (k ? ", " : "") + jsonNumber(values[k]);
    }
    members_.push_back({key, list + "]", nullptr});
    return *this;
}


JsonObject& JsonObject::add(const std::string& key, const JsonObject& value)
{
    members_.push_back({key, "", std::make_shared<JsonObject>(value)});
    return *this;
}


std::string JsonObject::text(int indent) const
{
    const std::string pad(2*(indent + 1), ' ');
    std::string out = "{\n";
    for (std::size_t k = 0; k < members_.size(); ++k)
    {
        const Member& m = members_[k];
        out += pad + quoted(m.key) + ": " + (m.object ? m.object->text(indent + 1) : m.value);
        out += k + 1 < members_.size() ? ",\n" : "\n";
    }
    return out + std::string(2*indent, ' ') + "}";
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
