#include "CommandLine.H"

#include "InputError.H"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <set>
#include <utility>

namespace iceDEM
{

CommandLine::CommandLine(std::string application)
:
    application_(std::move(application))
{}


CommandLine& CommandLine::add(Option option)
{
    if (find(option.name))
    {
        throw std::logic_error("CommandLine: option " + option.name + " declared twice");
    }
    options_.push_back(std::move(option));
    return *this;
}


const CommandLine::Option* CommandLine::find(const std::string& name) const
{
    for (const Option& o : options_)
    {
        if (o.name == name) return &o;
    }
    return nullptr;
}


double CommandLine::readNumber(const std::string& option, const std::string& value)
{
    const char* begin = value.c_str();
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(begin, &end);
    if (value.empty() || end != begin + value.size() || errno == ERANGE || !std::isfinite(x))
    {
        throw InputError("command line", option, "'" + value + "' is not a number");
    }
    return x;
}


long CommandLine::readWholeNumber(const std::string& option, const std::string& value)
{
    const char* begin = value.c_str();
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(begin, &end, 10);
    if (value.empty() || end != begin + value.size() || errno == ERANGE)
    {
        throw InputError("command line", option, "'" + value + "' is not a whole number");
    }
    return n;
}


CommandLine& CommandLine::text
(
    const std::string& name,
    const std::string& meta,
    const std::string& help,
    std::string& target
)
{
    return add({name, meta, help, [name, &target](const std::string& v)
    {
        if (v.empty())
        {
            throw InputError("command line", name, "needs a non-empty value");
        }
        target = v;
    }});
}


CommandLine& CommandLine::choice
(
    const std::string& name,
    const std::vector<std::string>& allowed,
    const std::string& help,
    std::string& target
)
{
    std::string meta;
    for (const std::string& a : allowed) meta += (meta.empty() ? "" : "|") + a;
    return add({name, meta, help, [name, allowed, &target](const std::string& v)
    {
        for (const std::string& a : allowed)
        {
            if (v == a)
            {
                target = v;
                return;
            }
        }
        std::string list;
        for (const std::string& a : allowed) list += " " + a;
        throw InputError("command line", name, "'" + v + "' is not one of:" + list);
    }});
}


CommandLine& CommandLine::positive
(
    const std::string& name,
    const std::string& meta,
    const std::string& help,
    double& target
)
{
    return add({name, meta, help, [name, &target](const std::string& v)
    {
        const double x = readNumber(name, v);
        if (!(x > 0.0))
        {
            throw InputError("command line", name, "needs a positive number, got '" + v + "'");
        }
        target = x;
    }});
}


CommandLine& CommandLine::count
(
    const std::string& name,
    const std::string& meta,
    const std::string& help,
    long minimum,
    long& target
)
{
    return add({name, meta, help, [name, minimum, &target](const std::string& v)
    {
        const long n = readWholeNumber(name, v);
        if (n < minimum)
        {
            throw InputError("command line", name,
                "needs a whole number of at least " + std::to_string(minimum) + ", got '" + v + "'");
        }
        target = n;
    }});
}


CommandLine& CommandLine::count
(
    const std::string& name,
    const std::string& meta,
    const std::string& help,
    long minimum,
    int& target
)
{
    return add({name, meta, help, [name, minimum, &target](const std::string& v)
    {
        const long n = readWholeNumber(name, v);
        if (n < minimum || n > INT_MAX)
        {
            throw InputError("command line", name,
                "needs a whole number from " + std::to_string(minimum) + " to " + std::to_string(INT_MAX)
              + ", got '" + v + "'");
        }
        target = static_cast<int>(n);
    }});
}


CommandLine& CommandLine::flag(const std::string& name, const std::string& help, bool& target)
{
    return add({name, "", help, [&target](const std::string&) { target = true; }});
}


void CommandLine::parse(int argc, char** argv) const
{
    std::set<std::string> given;
    for (int k = 1; k < argc; ++k)
    {
        const std::string arg = argv[k];
        if (arg == "-help" || arg == "--help")
        {
            throw HelpRequested(help());
        }
        const Option* option = find(arg);
        if (!option)
        {
            throw InputError("command line", arg, "unknown option; " + usage());
        }
        if (!given.insert(arg).second)
        {
            throw InputError("command line", arg, "given twice");
        }
        if (option->meta.empty())
        {
            option->set("");
            continue;
        }
        if (k + 1 >= argc)
        {
            throw InputError("command line", arg, "needs a value (" + option->meta + "); " + usage());
        }
        option->set(argv[++k]);
    }
}


std::string CommandLine::usage() const
{
    std::string u = "usage: " + application_ + " [-help]";
    for (const Option& o : options_)
    {
        u += " [" + o.name + (o.meta.empty() ? "" : " " + o.meta) + "]";
    }
    return u;
}


std::string CommandLine::help() const
{
    std::string h = usage();
    for (const Option& o : options_)
    {
        h += "\n    " + o.name + (o.meta.empty() ? "" : " " + o.meta) + ": " + o.help;
    }
    return h + "\n    -help: print this text and exit";
}

} // namespace iceDEM
