#include "Dictionary.H"
#include "IceBlocks.H"
#include "IceTypes.H"
#include "InputError.H"
#include "NamedEnum.H"
#include "WaterProperties.H"

#include <gtest/gtest.h>

using namespace iceDEM;

namespace
{

enum class Colour { red, green, blue };

const NamedEnum<Colour> colourNames
{{
    {Colour::red, "red"},
    {Colour::green, "green"},
    {Colour::blue, "blue"},
}};

//- Round trip of every name of a table: name -> value -> name.
template<class E>
void expectRoundTrip(const NamedEnum<E>& names)
{
    for (const std::string& n : names.names())
    {
        EXPECT_EQ(names.name(names.value(n)), n);
    }
}

} // namespace


TEST(NamedEnum, NamesRoundTripInTableOrder)
{
    EXPECT_EQ(colourNames.names(), (std::vector<std::string>{"red", "green", "blue"}));
    EXPECT_EQ(colourNames.name(Colour::green), "green");
    EXPECT_EQ(colourNames.value("blue"), Colour::blue);
    EXPECT_TRUE(colourNames.found("red"));
    EXPECT_FALSE(colourNames.found("Red"));
    expectRoundTrip(colourNames);
    expectRoundTrip(bondFamilyNames);
    expectRoundTrip(breakModeNames);
    expectRoundTrip(strengthModelNames);
    expectRoundTrip(breakageCriterionNames);
    expectRoundTrip(dampingModelNames);
    expectRoundTrip(waterLevelNames);
    expectRoundTrip(hydrostaticDragNames);
    expectRoundTrip(blockShapeNames);
}


TEST(NamedEnum, ValuesOutsideTheTable)
{
    EXPECT_EQ(breakModeNames.nameOr(static_cast<BreakMode>(9), "unknown"), "unknown");
    EXPECT_EQ(toString(static_cast<BreakMode>(9)), "unknown");
    EXPECT_THROW(breakModeNames.name(static_cast<BreakMode>(9)), std::logic_error);
    EXPECT_THROW(colourNames.value("purple"), std::invalid_argument);
}


TEST(NamedEnum, ReadsAChoiceFromADictionary)
{
    const Dictionary d = Dictionary::parse("paint green;", "colours");
    EXPECT_EQ(colourNames.get(d, "paint"), Colour::green);
    EXPECT_EQ(colourNames.getOrDefault(d, "trim", Colour::red), Colour::red);
    EXPECT_EQ(colourNames.getOrDefault(d, "paint", Colour::red), Colour::green);
}


TEST(NamedEnum, UnknownNameGivesFileLineEntryAndAllowedNames)
{
    const Dictionary d = Dictionary::parse("box\n{\n    paint purple;\n}\n", "colours");
    try
    {
        colourNames.get(d.subDict("box"), "paint");
        FAIL() << "purple accepted";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), "colours");
        EXPECT_EQ(e.entry(), "box.paint");
        const std::string what = e.what();
        EXPECT_NE(what.find("line 3"), std::string::npos) << what;
        EXPECT_NE(what.find("unknown value 'purple'; allowed: red green blue"), std::string::npos) << what;
    }
    // The same message as a Dictionary::getChoice with the names written out.
    std::string viaNamedEnum, viaDictionary;
    try { colourNames.getOrDefault(d.subDict("box"), "paint", Colour::red); }
    catch (const InputError& e) { viaNamedEnum = e.what(); }
    try { d.subDict("box").getChoice("paint", {"red", "green", "blue"}); }
    catch (const InputError& e) { viaDictionary = e.what(); }
    EXPECT_EQ(viaNamedEnum, viaDictionary);
}
