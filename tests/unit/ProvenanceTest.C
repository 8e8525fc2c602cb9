#include "Dictionary.H"
#include "InputError.H"
#include "Provenance.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace iceDEM;

namespace
{

std::string messageOf(const Provenance& stored, const Provenance& now)
{
    try
    {
        requireSameInputs(stored, now, "DEM/ridge.h5", "ridgeDEM -stage assemble");
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), "DEM/ridge.h5");
        EXPECT_EQ(e.entry(), "inputs");
        return e.what();
    }
    return "";
}

Provenance sample()
{
    Provenance p;
    p.add("constant/ridgeProperties/consolidatedLayer.thickness", "0.2");
    p.add("constant/freezeBondProperties/fixedSetCoeffs.set", "4h");
    p.add("command line -platenSpeed", "not given");
    return p;
}

} // namespace


TEST(Provenance, FingerprintIsTheSameForTheSameInputsInAnyOrder)
{
    Provenance a = sample(), b;
    b.add("command line -platenSpeed", "not given");
    b.add("constant/freezeBondProperties/fixedSetCoeffs.set", "4h");
    b.add("constant/ridgeProperties/consolidatedLayer.thickness", "0.2");
    EXPECT_EQ(a.fingerprint(), b.fingerprint());
    EXPECT_EQ(a.fingerprint().size(), 16u);
    b.add("constant/ridgeProperties/consolidatedLayer.thickness", "0.15");
    EXPECT_NE(a.fingerprint(), b.fingerprint());
}

TEST(Provenance, FnvHashOfKnownText)
{
    // FNV-1a 64 reference values (the empty string is the offset basis).
    EXPECT_EQ(fnv1aHex(""), "cbf29ce484222325");
    EXPECT_EQ(fnv1aHex("a"), "af63dc4c8601ec8c");
}

TEST(Provenance, TextRoundTrips)
{
    const Provenance a = sample();
    const Provenance b = Provenance::fromText(a.text());
    EXPECT_EQ(a.text(), b.text());
    EXPECT_TRUE(a.differences(b).empty());
    EXPECT_EQ(b.value("constant/freezeBondProperties/fixedSetCoeffs.set"), "4h");
    EXPECT_EQ(b.value("no such input"), "");
}

TEST(Provenance, SameInputsPass)
{
    EXPECT_EQ(messageOf(sample(), sample()), "");
}

TEST(Provenance, ChangedInputIsNamedWithBothValuesAndTheRebuildCommand)
{
    Provenance now = sample();
    now.add("constant/freezeBondProperties/fixedSetCoeffs.set", "ultimate");
    const std::string what = messageOf(sample(), now);
    EXPECT_NE(what.find("1 differ"), std::string::npos) << what;
    EXPECT_NE(what.find("constant/freezeBondProperties/fixedSetCoeffs.set: '4h' when it was made, 'ultimate' now"),
              std::string::npos) << what;
    EXPECT_NE(what.find("ridgeDEM -stage assemble"), std::string::npos) << what;
    EXPECT_EQ(what.find("thickness"), std::string::npos) << what;
}

TEST(Provenance, InputOnOneSideOnlyIsADifference)
{
    Provenance now = sample();
    now.add("constant/ridgeProperties/box.length", "1.6");
    const std::string what = messageOf(sample(), now);
    EXPECT_NE(what.find("box.length: absent when it was made, '1.6' now"), std::string::npos) << what;
}

TEST(Provenance, AFileWithoutARecordIsRefused)
{
    const std::string what = messageOf(Provenance(), sample());
    EXPECT_NE(what.find("no record of the inputs"), std::string::npos) << what;
    EXPECT_NE(what.find("ridgeDEM -stage assemble"), std::string::npos) << what;
}

TEST(Provenance, DictionaryEntriesAreReadAsResolvedWithIgnoredKeywordsLeftOut)
{
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "iceDEM_provenance_test";
    std::filesystem::create_directories(dir / "common");
    std::filesystem::create_directories(dir / "case" / "system");
    std::ofstream(dir / "common" / "control") << "maxTravel 0.1;\nwriteInterval 0.01;\n";
    std::ofstream(dir / "case" / "system" / "controlDict")
        << "#include \"../../common/control\"\nspeed $maxTravel;\nsub { a 1; b (1 2 3); }\n";
    Provenance p;
    p.addDictionaryFile("system/controlDict", (dir / "case" / "system" / "controlDict").string(), {"writeInterval"});
    EXPECT_EQ(p.value("system/controlDict/maxTravel"), "0.1");
    EXPECT_EQ(p.value("system/controlDict/speed"), "0.1");
    EXPECT_EQ(p.value("system/controlDict/sub.b"), "( 1 2 3 )");
    EXPECT_EQ(p.value("system/controlDict/writeInterval"), "");
    std::filesystem::remove_all(dir);
}

TEST(Provenance, AnEntryOfASubDictionaryIsLeftOutByItsDottedPath)
{
    // rubbleDEM -shape overrides blocks.shape: the dictionary's own value is not an input
    const Dictionary d = Dictionary::parse("blocks { shape cuboid; thickness 0.1; }\nshape keep;\n"
                                           "ends { fixedLength 0.1; }\n", "rubbleProperties");
    Provenance p;
    p.addDictionary("constant/rubbleProperties", d, {"ends", "blocks.shape"});
    EXPECT_EQ(p.value("constant/rubbleProperties/blocks.shape"), "");
    EXPECT_EQ(p.value("constant/rubbleProperties/blocks.thickness"), "0.1");
    EXPECT_EQ(p.value("constant/rubbleProperties/shape"), "keep");
    EXPECT_EQ(p.value("constant/rubbleProperties/ends.fixedLength"), "");
}

TEST(Provenance, AStageIsRecordedByItsFingerprint)
{
    Provenance keel;
    keel.add("constant/rubbleProperties/box.length", "1.6");
    Provenance ridge;
    ridge.addStage("DEM/settled.h5", keel);
    EXPECT_EQ(ridge.value("DEM/settled.h5"), "fingerprint " + keel.fingerprint());
    Provenance unknown;
    unknown.addStage("DEM/settled.h5", Provenance());
    EXPECT_EQ(unknown.value("DEM/settled.h5"), "unknown");
}
