#include "Dictionary.H"
#include "InputError.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace iceDEM;

namespace
{

//- The message of the InputError thrown by f ("" and a test failure if none).
template<class F>
std::string errorOf(F f)
{
    try
    {
        f();
    }
    catch (const InputError& e)
    {
        return e.what();
    }
    ADD_FAILURE() << "expected an InputError";
    return "";
}

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) \
        << "'" << (text) << "' does not contain '" << (part) << "'"

Dictionary parse(const std::string& text)
{
    return Dictionary::parse(text, "testDict");
}

} // namespace


TEST(Dictionary, HeaderIsParsedAndIgnored)
{
    const Dictionary d = parse
    (
        "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
        "    object iceProperties;\n}\n"
        "a 1;\n"
    );
    EXPECT_FALSE(d.found("FoamFile"));
    EXPECT_EQ(d.keys(), std::vector<std::string>{"a"});
}


TEST(Dictionary, NestedSubDictionariesAndDottedPaths)
{
    const Dictionary d = parse
    (
        "outer\n{\n    x 1;\n    middle\n    {\n        inner { y 2.5; }\n    }\n}\nz 3;\n"
    );
    ASSERT_TRUE(d.isDict("outer"));
    EXPECT_FALSE(d.isDict("z"));
    EXPECT_FALSE(d.isDict("nothing"));
    const Dictionary& inner = d.subDict("outer").subDict("middle").subDict("inner");
    EXPECT_EQ(inner.path(), "outer.middle.inner");
    EXPECT_EQ(inner.entryPath("y"), "outer.middle.inner.y");
    EXPECT_EQ(inner.line(), 6);
    EXPECT_DOUBLE_EQ(inner.getScalar("y"), 2.5);
    EXPECT_DOUBLE_EQ(d.subDict("outer").getScalar("x"), 1.0);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"outer", "z"}));
    EXPECT_EQ(d.subDict("outer").keys(), (std::vector<std::string>{"x", "middle"}));

    const std::string msg = errorOf([&] { inner.getScalar("missing"); });
    EXPECT_CONTAINS(msg, "testDict");
    EXPECT_CONTAINS(msg, "'outer.middle.inner.missing'");
    EXPECT_CONTAINS(msg, "missing; expected a number");
}


TEST(Dictionary, CommentsAreSkipped)
{
    const Dictionary d = parse
    (
        "// line comment a 99;\n"
        "a 1; // trailing\n"
        "/* block\n   b 99;\n*/ b /* inside */ 2;\n"
        "c 3;// no space\n"
        "path \"x//y/*z*/\";\n"
        "e 4/*glued*/;\n"
    );
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"a", "b", "c", "path", "e"}));
    EXPECT_DOUBLE_EQ(d.getScalar("a"), 1);
    EXPECT_DOUBLE_EQ(d.getScalar("b"), 2);
    EXPECT_DOUBLE_EQ(d.getScalar("c"), 3);
    EXPECT_EQ(d.getString("path"), "x//y/*z*/");
    EXPECT_DOUBLE_EQ(d.getScalar("e"), 4);
}


TEST(Dictionary, ScalarsAndLabels)
{
    const Dictionary d = parse
    (
        "e 5.4e8; neg -3; plus +2; frac .5; small 1e-3; n 16; half 1.5; big 1e3; word abc;"
        " huge 99999999999; inf inf; nan nan; two 1 2; sub { }\n"
    );
    EXPECT_DOUBLE_EQ(d.getScalar("e"), 5.4e8);
    EXPECT_DOUBLE_EQ(d.getScalar("neg"), -3);
    EXPECT_DOUBLE_EQ(d.getScalar("plus"), 2);
    EXPECT_DOUBLE_EQ(d.getScalar("frac"), 0.5);
    EXPECT_DOUBLE_EQ(d.getScalar("small"), 1e-3);
    EXPECT_DOUBLE_EQ(d.getScalarOrDefault("absent", 7.0), 7.0);
    EXPECT_DOUBLE_EQ(d.getScalarOrDefault("e", 7.0), 5.4e8);
    EXPECT_EQ(d.getLabel("n"), 16);
    EXPECT_EQ(d.getLabel("neg"), -3);
    EXPECT_EQ(d.getLabelOrDefault("absent", 4), 4);

    EXPECT_CONTAINS(errorOf([&] { d.getLabel("half"); }), "'1.5' is not an integer");
    EXPECT_CONTAINS(errorOf([&] { d.getLabel("big"); }), "'1e3' is not an integer");
    EXPECT_CONTAINS(errorOf([&] { d.getLabel("huge"); }), "out of the integer range");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("word"); }), "'abc' is not a number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("inf"); }), "not a finite number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("nan"); }), "not a finite number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("two"); }), "found '1 2'; expected a number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("sub"); }), "is a sub-dictionary");
    EXPECT_CONTAINS(errorOf([&] { d.subDict("e"); }), "expected a sub-dictionary");
}


TEST(Dictionary, WordsStringsAndChoices)
{
    const Dictionary d = parse("m hysteretic; s \"two words\"; bad foo;\n");
    EXPECT_EQ(d.getWord("m"), "hysteretic");
    EXPECT_EQ(d.getString("s"), "two words");
    EXPECT_EQ(d.getString("m"), "hysteretic");
    EXPECT_CONTAINS(errorOf([&] { d.getWord("s"); }), "quoted string");
    EXPECT_EQ(d.getChoice("m", {"none", "hysteretic", "viscous"}), "hysteretic");
    EXPECT_EQ(d.getChoiceOrDefault("absent", {"a", "b"}, "b"), "b");

    const std::string msg = errorOf([&] { d.getChoice("bad", {"none", "hysteretic", "viscous"}); });
    EXPECT_CONTAINS(msg, "'bad'");
    EXPECT_CONTAINS(msg, "unknown value 'foo'; allowed: none hysteretic viscous");
}


TEST(Dictionary, Booleans)
{
    const Dictionary d = parse("a true; b false; c yes; d no; e on; f off; g maybe; h 1;\n");
    EXPECT_TRUE(d.getBool("a"));
    EXPECT_FALSE(d.getBool("b"));
    EXPECT_TRUE(d.getBool("c"));
    EXPECT_FALSE(d.getBool("d"));
    EXPECT_TRUE(d.getBool("e"));
    EXPECT_FALSE(d.getBool("f"));
    EXPECT_TRUE(d.getBoolOrDefault("absent", true));
    EXPECT_FALSE(d.getBoolOrDefault("b", true));
    EXPECT_CONTAINS(errorOf([&] { d.getBool("g"); }), "'maybe' is not a boolean");
    EXPECT_CONTAINS(errorOf([&] { d.getBool("h"); }), "allowed: true false yes no on off");
}


TEST(Dictionary, Lists)
{
    const Dictionary d = parse
    (
        "a (1 2.5 -3e2);\n"
        "b 3(4 5 6);\n"
        "empty ();\n"
        "multi\n(\n    1\n    2\n);\n"
        "wrongSize 2(1 2 3);\n"
        "word (1 x 3);\n"
        "nested ((1 2) (3 4));\n"
        "notList 5;\n"
        "mixed (name { type wall; } 1);\n"
    );
    EXPECT_EQ(d.getScalarList("a"), (std::vector<double>{1, 2.5, -300}));
    EXPECT_EQ(d.getScalarList("b"), (std::vector<double>{4, 5, 6}));
    EXPECT_TRUE(d.getScalarList("empty").empty());
    EXPECT_EQ(d.getScalarList("multi"), (std::vector<double>{1, 2}));
    EXPECT_CONTAINS(errorOf([&] { d.getScalarList("wrongSize"); }), "does not match");
    EXPECT_CONTAINS(errorOf([&] { d.getScalarList("word"); }), "'x' is not a number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalarList("nested"); }), "'(' is not a number");
    EXPECT_CONTAINS(errorOf([&] { d.getScalarList("notList"); }), "expected a list");
    // A list may hold anything bracketed, even a dictionary; it is kept as tokens.
    EXPECT_TRUE(d.found("mixed"));
    EXPECT_EQ(d.entry("mixed").tokens.size(), 9u);
}


TEST(Dictionary, StraySemicolonAfterSubDictIsAccepted)
{
    const Dictionary d = parse("a { b 1; };\nc 2;\n");
    EXPECT_DOUBLE_EQ(d.subDict("a").getScalar("b"), 1);
    EXPECT_DOUBLE_EQ(d.getScalar("c"), 2);
}


TEST(Dictionary, ValueErrorsCarryLineNumbers)
{
    const Dictionary d = parse("\n\nsub\n{\n    x abc;\n}\n");
    const std::string msg = errorOf([&] { d.subDict("sub").getScalar("x"); });
    EXPECT_CONTAINS(msg, "testDict: entry 'sub.x': line 5: 'abc' is not a number");
}


TEST(Dictionary, MissingSemicolonIsHintedAtValueUse)
{
    const Dictionary d = parse("a 1\nb 2;\n");
    EXPECT_CONTAINS(errorOf([&] { d.getScalar("a"); }), "missing ';' at line 1?");
}


TEST(Dictionary, SyntaxErrorsNameFileAndLine)
{
    struct Case { std::string text; std::string part; };
    const std::vector<Case> cases =
    {
        {"a 1;\nb 2", "line 2: missing ';'"},
        {"a 1;\nsub\n{\n  x 1;\n", "line 3: '{' of 'sub' is never closed"},
        {"a 1;\n}\n", "line 2: '}' without a matching '{'"},
        {"a 1;\n/* open\n\n", "line 2: comment '/*' is never closed"},
        {"a 1;\n\n\ns \"open;\n", "line 4: string opened with '\"' is never closed"},
        {"a 1;\nb 2;\na 3;\n", "line 3: duplicate entry (first defined at line 1)"},
        {"l (1 2;\n", "line 1: '(' is never closed"},
        {"l (1 2));\n", "line 1: ')' does not match any opening bracket"},
        {"l (1 2};\n", "line 1: '}' does not match '(' of line 1"},
        {"sub { x 1 }\n", "line 1: missing ';' before '}'"},
        {"a;\n", "line 1: entry has no value"},
        {"\n#include \"other\"\n", "line 2: directives"},
        {"\"quoted\" 1;\n", "expected a keyword"},
        {"FoamFile 2;\n", "FoamFile header must be a dictionary"},
    };
    for (const Case& c : cases)
    {
        const std::string msg = errorOf([&] { parse(c.text); });
        EXPECT_CONTAINS(msg, "testDict: ");
        EXPECT_CONTAINS(msg, c.part);
    }
    EXPECT_CONTAINS(errorOf([&] { parse("sub { x 1; }\nsub { y 1; }\n"); }), "entry 'sub'");
    EXPECT_CONTAINS(errorOf([&] { parse("a { b { c 1 } }\n"); }), "entry 'a.b.c'");
}


TEST(Dictionary, CheckKeysSuggestsAndListsAllowed)
{
    const Dictionary d = parse("s { youngModulus 1; density 2; }\n");
    const Dictionary& s = d.subDict("s");
    EXPECT_NO_THROW(s.checkKeys({"youngModulus", "density"}));
    const std::string msg = errorOf([&] { s.checkKeys({"density", "youngsModulus"}); });
    EXPECT_CONTAINS(msg, "entry 's.youngModulus': line 1: unknown keyword");
    EXPECT_CONTAINS(msg, "did you mean 'youngsModulus'?");
    EXPECT_CONTAINS(msg, "allowed: density youngsModulus");
}


TEST(Dictionary, ReadFileAndMissingFile)
{
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "iceDEM_DictionaryTest";
    std::filesystem::create_directories(dir);
    const std::string file = (dir / "someDict").string();
    {
        std::ofstream out(file);
        out << "FoamFile { version 2.0; format ascii; class dictionary; object someDict; }\n"
            << "values (1 2);\nflag on;\n";
    }
    const Dictionary d = Dictionary::readFile(file);
    EXPECT_EQ(d.fileName(), file);
    EXPECT_EQ(d.getScalarList("values"), (std::vector<double>{1, 2}));
    EXPECT_TRUE(d.getBool("flag"));

    const std::string missing = (dir / "doesNotExist").string();
    const std::string msg = errorOf([&] { Dictionary::readFile(missing); });
    EXPECT_CONTAINS(msg, missing);
    EXPECT_CONTAINS(msg, "cannot open the file");
    std::filesystem::remove_all(dir);
}
