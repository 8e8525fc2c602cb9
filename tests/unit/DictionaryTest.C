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
        {"\n#calc \"1 + 2\";\n", "line 2: directive '#calc' is not supported"},
        {"#include;\n", "line 1: #include needs a file name"},
        {"a ${b;\n", "line 1: '${' is not closed"},
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


// * * * * * * * * * * * * * * #include and $variables * * * * * * * * * * * //

namespace
{

//- A fresh temporary directory, removed with the object.
class TempDir
{
public:
    explicit TempDir(const std::string& name)
    :
        path_(std::filesystem::temp_directory_path() / ("iceDEM_DictionaryTest_" + name))
    {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }

    //- Writes text to the relative path (directories created); its full path.
    std::string write(const std::string& relative, const std::string& text) const
    {
        const std::filesystem::path file = path_ / relative;
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file) << text;
        return file.string();
    }

    std::string path(const std::string& relative) const { return (path_ / relative).string(); }

private:
    std::filesystem::path path_;
};

const char* const header =
    "FoamFile { version 2.0; format ascii; class dictionary; object common; }\n";

} // namespace


TEST(DictionaryInclude, RelativeToTheIncludersFolder)
{
    const TempDir dir("relative");
    dir.write("common/ice", std::string(header) + "density 917;\nyoungsModulus 5.4e8;\n");
    const std::string caseFile = dir.write
    (
        "case/constant/ice",
        std::string(header) + "#include \"../../common/ice\"\nextra 1;\n"
    );
    const Dictionary d = Dictionary::readFile(caseFile);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"density", "youngsModulus", "extra"}));
    EXPECT_DOUBLE_EQ(d.getScalar("density"), 917);
    EXPECT_EQ(d.entry("density").fileName, dir.path("common/ice"));
    EXPECT_EQ(d.entry("extra").fileName, caseFile);
}


TEST(DictionaryInclude, AbsolutePathAndInsideSubDictionary)
{
    const TempDir dir("absolute");
    const std::string common = dir.write("elsewhere/family", "breakN 0.0037;\nbeta 1.25;\n");
    const std::string file = dir.write("d", "families { ice { #include \"" + common + "\" } }\n");
    const Dictionary d = Dictionary::readFile(file);
    const Dictionary& ice = d.subDict("families").subDict("ice");
    EXPECT_DOUBLE_EQ(ice.getScalar("breakN"), 0.0037);
    EXPECT_EQ(ice.entryPath("beta"), "families.ice.beta");
}


TEST(DictionaryInclude, NestedIncludesResolveFromEachFile)
{
    const TempDir dir("nested");
    dir.write("a/b/inner", "inner 2;\n");
    dir.write("a/middle", "#include \"b/inner\"\nmiddle 1;\n");
    const std::string top = dir.write("top/dict", "#include \"../a/middle\"\ntop 0;\n");
    const Dictionary d = Dictionary::readFile(top);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"inner", "middle", "top"}));
}


TEST(DictionaryInclude, LaterEntriesOverrideAndSubDictionariesMerge)
{
    const TempDir dir("override");
    dir.write
    (
        "common",
        std::string(header)
      + "material { density 917; youngsModulus 1.95e8; }\n"
        "damping { model hysteretic; coeffs { alpha 0.1; } }\n"
        "factor 0.25;\nlist (1 2);\n"
    );
    const std::string file = dir.write
    (
        "case",
        "#include \"common\"\n"
        "factor 0.2;\n"
        "material { youngsModulus 5.4e8; }\n"
        "damping { coeffs { alpha 0.2; beta 1; } }\n"
        "list 3;\n"
    );
    const Dictionary d = Dictionary::readFile(file);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"material", "damping", "factor", "list"}));
    EXPECT_DOUBLE_EQ(d.getScalar("factor"), 0.2);
    EXPECT_EQ(d.entry("factor").line, 2);
    EXPECT_DOUBLE_EQ(d.getScalar("list"), 3);
    const Dictionary& material = d.subDict("material");
    EXPECT_EQ(material.keys(), (std::vector<std::string>{"density", "youngsModulus"}));
    EXPECT_DOUBLE_EQ(material.getScalar("density"), 917);
    EXPECT_DOUBLE_EQ(material.getScalar("youngsModulus"), 5.4e8);
    EXPECT_EQ(d.subDict("damping").getWord("model"), "hysteretic");
    const Dictionary& coeffs = d.subDict("damping").subDict("coeffs");
    EXPECT_DOUBLE_EQ(coeffs.getScalar("alpha"), 0.2);
    EXPECT_DOUBLE_EQ(coeffs.getScalar("beta"), 1);
    EXPECT_EQ(coeffs.path(), "damping.coeffs");
}


TEST(DictionaryInclude, ErrorsInsideAnIncludedFileNameThatFile)
{
    const TempDir dir("innerError");
    const std::string common = dir.write("common", "\n\nsub { x abc; }\nbroken 1\n");
    const std::string file = dir.write("case", "#include \"common\"\n");
    const std::string syntax = errorOf([&] { Dictionary::readFile(file); });
    EXPECT_CONTAINS(syntax, common + ": entry 'broken': line 4: missing ';'");

    dir.write("common", "\n\nsub { x abc; }\n");
    const Dictionary d = Dictionary::readFile(file);
    EXPECT_CONTAINS
    (
        errorOf([&] { d.subDict("sub").getScalar("x"); }),
        common + ": entry 'sub.x': line 3: 'abc' is not a number"
    );
}


TEST(DictionaryInclude, UnknownKeyAfterIncludeIsStillRefused)
{
    const TempDir dir("unknownKey");
    dir.write("common", "s { youngsModulus 1; density 2; }\n");
    const std::string file = dir.write("case", "#include \"common\"\n\ns { densty 3; }\n");
    const Dictionary d = Dictionary::readFile(file);
    const std::string msg = errorOf([&] { d.subDict("s").checkKeys({"youngsModulus", "density"}); });
    EXPECT_CONTAINS(msg, file + ": entry 's.densty': line 3: unknown keyword");
    EXPECT_CONTAINS(msg, "did you mean 'density'?");
}


TEST(DictionaryInclude, MissingFileNamesIncluderLineAndPathTried)
{
    const TempDir dir("missing");
    const std::string file = dir.write("constant/case", "a 1;\n\nsub\n{\n    #include \"../nothing/here\"\n}\n");
    const std::string msg = errorOf([&] { Dictionary::readFile(file); });
    EXPECT_CONTAINS(msg, file + ": entry 'sub.#include': line 5: ");
    EXPECT_CONTAINS(msg, "cannot open the included file \"../nothing/here\"");
    EXPECT_CONTAINS(msg, "tried '" + dir.path("nothing/here") + "'");

    const std::string optional = dir.write("optional", "#includeIfPresent \"absent\"\na 1;\n");
    EXPECT_EQ(Dictionary::readFile(optional).keys(), std::vector<std::string>{"a"});
}


TEST(DictionaryInclude, CycleIsRefused)
{
    const TempDir dir("cycle");
    dir.write("a", "x 1;\n#include \"b\"\n");
    dir.write("b", "y 1;\n\n#include \"a\"\n");
    const std::string msg = errorOf([&] { Dictionary::readFile(dir.path("a")); });
    EXPECT_CONTAINS(msg, dir.path("b") + ": entry '#include': line 3: include cycle");
    EXPECT_CONTAINS(msg, dir.path("a") + " -> " + dir.path("b") + " -> " + dir.path("a"));

    dir.write("self", "#include \"self\"\n");
    EXPECT_CONTAINS(errorOf([&] { Dictionary::readFile(dir.path("self")); }), "include cycle");
}


TEST(DictionaryVariables, WholeValueAndOneTokenFromEnclosingScopes)
{
    const Dictionary d = parse
    (
        "E 5.4e8;\nn 3;\n"
        "material { youngsModulus $E; }\n"
        "outer { E 1; inner { e $E; } }\n"
        "list ($n 4 ${n});\n"
        "quoted \"$E\";\n"
    );
    EXPECT_DOUBLE_EQ(d.subDict("material").getScalar("youngsModulus"), 5.4e8);
    EXPECT_DOUBLE_EQ(d.subDict("outer").subDict("inner").getScalar("e"), 1);   // innermost wins
    EXPECT_EQ(d.getScalarList("list"), (std::vector<double>{3, 4, 3}));
    EXPECT_EQ(d.getString("quoted"), "$E");   // no expansion inside strings, as OpenFOAM
}


TEST(DictionaryVariables, AtThePointOfUseWithWhatIsAboveIt)
{
    const TempDir dir("pointOfUse");
    dir.write("common", "x 2;\n");
    const std::string file = dir.write("case", "x 1;\ny $x;\n#include \"common\"\nz $x;\n");
    const Dictionary d = Dictionary::readFile(file);
    EXPECT_DOUBLE_EQ(d.getScalar("y"), 1);
    EXPECT_DOUBLE_EQ(d.getScalar("z"), 2);
    EXPECT_DOUBLE_EQ(d.getScalar("x"), 2);
}


TEST(DictionaryVariables, ScopedNames)
{
    const Dictionary d = parse
    (
        "bondFamilies { ice { youngsModulus 5.4e8; beta 1.25; } }\n"
        "a { b { c 7; } }\n"
        "top 3;\n"
        "sub\n{\n"
        "    top 4;\n"
        "    e $bondFamilies.ice.youngsModulus;\n"
        "    c ${a.b.c};\n"
        "    fromTop $:top;\n"
        "    fromParent $..top;\n"
        "    slashed $/a/b/c;\n"
        "    here $top;\n"
        "}\n"
    );
    const Dictionary& sub = d.subDict("sub");
    EXPECT_DOUBLE_EQ(sub.getScalar("e"), 5.4e8);
    EXPECT_DOUBLE_EQ(sub.getScalar("c"), 7);
    EXPECT_DOUBLE_EQ(sub.getScalar("fromTop"), 3);
    EXPECT_DOUBLE_EQ(sub.getScalar("fromParent"), 3);
    EXPECT_DOUBLE_EQ(sub.getScalar("slashed"), 7);
    EXPECT_DOUBLE_EQ(sub.getScalar("here"), 4);
}


TEST(DictionaryVariables, CopyingASubDictionary)
{
    const Dictionary d = parse
    (
        "ice { distFactor 1.1; youngsModulus 5.4e8; coeffs { alpha 0.1; } }\n"
        "freeze { $ice; distFactor 1.0; extra 1; }\n"
        "copy { $ice; }\n"
    );
    const Dictionary& freeze = d.subDict("freeze");
    EXPECT_EQ(freeze.keys(), (std::vector<std::string>{"distFactor", "youngsModulus", "coeffs", "extra"}));
    EXPECT_DOUBLE_EQ(freeze.getScalar("distFactor"), 1.0);
    EXPECT_DOUBLE_EQ(freeze.getScalar("youngsModulus"), 5.4e8);
    EXPECT_EQ(freeze.subDict("coeffs").path(), "freeze.coeffs");
    EXPECT_DOUBLE_EQ(d.subDict("copy").getScalar("distFactor"), 1.1);
    EXPECT_EQ(d.subDict("copy").subDict("coeffs").entryPath("alpha"), "copy.coeffs.alpha");
    EXPECT_DOUBLE_EQ(d.subDict("ice").getScalar("distFactor"), 1.1);   // the original is untouched
}


TEST(DictionaryVariables, UndefinedOrMisusedNameTheFileLineAndVariable)
{
    const std::string undefined = errorOf([&] { parse("a 1;\nsub { x $nowhereDefined1; }\n"); });
    EXPECT_CONTAINS(undefined, "testDict: entry 'sub.x': line 2: undefined variable '$nowhereDefined1'");

    EXPECT_CONTAINS(errorOf([&] { parse("b $a;\na 1;\n"); }), "undefined variable '$a'");
    EXPECT_CONTAINS(errorOf([&] { parse("a { x 1; }\nb { $a.y; }\n"); }), "undefined variable '$a.y'");
    EXPECT_CONTAINS
    (
        errorOf([&] { parse("a { x 1; }\nb (1 $a);\n"); }),
        "line 2: '$a' is a sub-dictionary; copy it with `b { $a; }`"
    );
    EXPECT_CONTAINS(errorOf([&] { parse("a { x 1; }\ns { b $a; }\n"); }), "entry 's.b'");
    EXPECT_CONTAINS
    (
        errorOf([&] { parse("a 1;\nb { $a; }\n"); }),
        "entry 'b.$a': line 2: '$a' is not a sub-dictionary"
    );

    const TempDir dir("undefinedVariable");
    dir.write("common", "\nx $missingVar;\n");
    const std::string file = dir.write("case", "#include \"common\"\n");
    EXPECT_CONTAINS
    (
        errorOf([&] { Dictionary::readFile(file); }),
        dir.path("common") + ": entry 'x': line 2: undefined variable '$missingVar'"
    );
}


TEST(DictionaryVariables, IncludedFileSeesTheIncludersEntries)
{
    const TempDir dir("includeScope");
    dir.write("common", "density $rho;\n");
    const std::string file = dir.write("case", "rho 917;\nice { #include \"common\" }\n");
    EXPECT_DOUBLE_EQ(Dictionary::readFile(file).subDict("ice").getScalar("density"), 917);
}


TEST(DictionaryVariables, EnvironmentVariableWhenNoEntry)
{
    ::setenv("ICEDEM_DICTIONARY_TEST_VAR", "42", 1);
    EXPECT_DOUBLE_EQ(parse("a $ICEDEM_DICTIONARY_TEST_VAR;\n").getScalar("a"), 42);
    ::unsetenv("ICEDEM_DICTIONARY_TEST_VAR");
}
