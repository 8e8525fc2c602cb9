#include "CommandLine.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace iceDEM;

namespace
{

struct Options
{
    std::string caseDir = ".";
    std::string stage = "all";
    int particles = 0;
    long steps = 0;
    double speed = 0.0;
    bool resume = false;
};

CommandLine declare(Options& o)
{
    CommandLine cl("testApp");
    cl.text("-case", "DIR", "the case", o.caseDir)
      .choice("-stage", {"settle", "bond", "all"}, "stage", o.stage)
      .count("-particles", "N", "particles", 20, o.particles)
      .count("-steps", "N", "steps", 1, o.steps)
      .positive("-platenSpeed", "M_PER_S", "speed", o.speed)
      .flag("-resume", "resume", o.resume);
    return cl;
}

void parse(Options& o, std::vector<std::string> args)
{
    args.insert(args.begin(), "testApp");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    declare(o).parse(static_cast<int>(argv.size()), argv.data());
}

//- The InputError's entry, or "" when the arguments are accepted.
std::string refusedEntry(std::vector<std::string> args)
{
    Options o;
    try
    {
        parse(o, args);
    }
    catch (const InputError& e)
    {
        return e.entry();
    }
    return "";
}

} // namespace


TEST(CommandLine, ReadsEveryKindOfOption)
{
    Options o;
    parse(o, {"-case", "runs/a", "-stage", "bond", "-particles", "400", "-steps", "12",
              "-platenSpeed", "0.05", "-resume"});
    EXPECT_EQ(o.caseDir, "runs/a");
    EXPECT_EQ(o.stage, "bond");
    EXPECT_EQ(o.particles, 400);
    EXPECT_EQ(o.steps, 12);
    EXPECT_DOUBLE_EQ(o.speed, 0.05);
    EXPECT_TRUE(o.resume);
}

TEST(CommandLine, AbsentOptionsKeepTheirDefaults)
{
    Options o;
    parse(o, {});
    EXPECT_EQ(o.caseDir, ".");
    EXPECT_EQ(o.particles, 0);
    EXPECT_DOUBLE_EQ(o.speed, 0.0);
    EXPECT_FALSE(o.resume);
}

TEST(CommandLine, NumbersMustBeTheWholeArgument)
{
    EXPECT_EQ(refusedEntry({"-particles", "400abc"}), "-particles");
    EXPECT_EQ(refusedEntry({"-particles", "1e3"}), "-particles");
    EXPECT_EQ(refusedEntry({"-particles", "4.5"}), "-particles");
    EXPECT_EQ(refusedEntry({"-platenSpeed", "0.1m/s"}), "-platenSpeed");
    EXPECT_EQ(refusedEntry({"-platenSpeed", "nan"}), "-platenSpeed");
    EXPECT_EQ(refusedEntry({"-platenSpeed", ""}), "-platenSpeed");
    EXPECT_EQ(refusedEntry({"-platenSpeed", "1e-3"}), "");
}

TEST(CommandLine, ZeroAndNegativesAreRefusedWhereTheyMeanNothing)
{
    EXPECT_EQ(refusedEntry({"-particles", "0"}), "-particles");
    EXPECT_EQ(refusedEntry({"-particles", "19"}), "-particles");
    EXPECT_EQ(refusedEntry({"-particles", "20"}), "");
    EXPECT_EQ(refusedEntry({"-steps", "0"}), "-steps");
    EXPECT_EQ(refusedEntry({"-steps", "-5"}), "-steps");
    EXPECT_EQ(refusedEntry({"-platenSpeed", "0"}), "-platenSpeed");
    EXPECT_EQ(refusedEntry({"-platenSpeed", "-0.1"}), "-platenSpeed");
    EXPECT_EQ(refusedEntry({"-particles", "99999999999"}), "-particles");
}

TEST(CommandLine, UnknownRepeatedAndIncompleteOptionsAreRefused)
{
    EXPECT_EQ(refusedEntry({"-partcles", "400"}), "-partcles");
    EXPECT_EQ(refusedEntry({"-resume", "-resume"}), "-resume");
    EXPECT_EQ(refusedEntry({"-case"}), "-case");
    EXPECT_EQ(refusedEntry({"-stage", "load"}), "-stage");
    EXPECT_EQ(refusedEntry({"extra"}), "extra");
}

TEST(CommandLine, UnknownOptionMessageCarriesTheUsage)
{
    Options o;
    try
    {
        parse(o, {"-bogus"});
        FAIL() << "accepted -bogus";
    }
    catch (const InputError& e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("unknown option"), std::string::npos) << what;
        EXPECT_NE(what.find("usage: testApp"), std::string::npos) << what;
        EXPECT_NE(what.find("[-particles N]"), std::string::npos) << what;
    }
}

TEST(CommandLine, HelpListsEveryOption)
{
    Options o;
    try
    {
        parse(o, {"-help"});
        FAIL() << "-help parsed as an option";
    }
    catch (const HelpRequested& help)
    {
        const std::string text = help.what();
        for (const char* name : {"-case DIR", "-stage settle|bond|all", "-particles N", "-steps N",
                                 "-platenSpeed M_PER_S", "-resume", "-help"})
        {
            EXPECT_NE(text.find(name), std::string::npos) << name << " missing from\n" << text;
        }
    }
}
