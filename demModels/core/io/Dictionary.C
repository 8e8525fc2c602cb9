#include "Dictionary.H"
#include "InputError.H"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

namespace iceDEM
{

namespace
{

const char* const syntaxEntry = "(syntax)";

std::string lineTag(int line)
{
    return "line " + std::to_string(line) + ": ";
}

bool isPunct(char c)
{
    return c == ';' || c == '{' || c == '}' || c == '(' || c == ')';
}

bool isPunct(const DictToken& t, char c)
{
    return t.kind == DictToken::Kind::punct && t.text[0] == c;
}

std::string render(const DictToken& t)
{
    return t.kind == DictToken::Kind::string ? "\"" + t.text + "\"" : t.text;
}

std::string render(const std::vector<DictToken>& tokens)
{
    std::string s;
    for (const DictToken& t : tokens)
    {
        if (!s.empty()) s += ' ';
        s += render(t);
    }
    return s;
}

std::string joined(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words)
    {
        if (!s.empty()) s += ' ';
        s += w;
    }
    return s;
}

//- A finite number, locale-independent; false if text is not one.
bool toScalar(const std::string& text, double& value)
{
    const char* first = text.data();
    const char* last = first + text.size();
    if (first != last && *first == '+') ++first;
    const auto [end, ec] = std::from_chars(first, last, value);
    return ec == std::errc() && end == last && first != last;
}

std::vector<DictToken> tokenise(const std::string& text, const std::string& fileName)
{
    std::vector<DictToken> tokens;
    const std::size_t n = text.size();
    std::size_t i = 0;
    int line = 1;

    auto startsComment = [&](std::size_t k)
    {
        return k + 1 < n && text[k] == '/' && (text[k + 1] == '/' || text[k + 1] == '*');
    };

    while (i < n)
    {
        const char c = text[i];
        if (c == '\n')
        {
            ++line;
            ++i;
        }
        else if (std::isspace(static_cast<unsigned char>(c)))
        {
            ++i;
        }
        else if (startsComment(i) && text[i + 1] == '/')
        {
            while (i < n && text[i] != '\n') ++i;
        }
        else if (startsComment(i))
        {
            const int startLine = line;
            i += 2;
            while (i + 1 < n && !(text[i] == '*' && text[i + 1] == '/'))
            {
                if (text[i] == '\n') ++line;
                ++i;
            }
            if (i + 1 >= n)
            {
                throw InputError
                (
                    fileName, syntaxEntry,
                    lineTag(startLine) + "comment '/*' is never closed by '*/'"
                );
            }
            i += 2;
        }
        else if (c == '"')
        {
            const int startLine = line;
            std::string s;
            ++i;
            while (i < n && text[i] != '"')
            {
                if (text[i] == '\\' && i + 1 < n && (text[i + 1] == '"' || text[i + 1] == '\\'))
                {
                    ++i;
                }
                if (text[i] == '\n') ++line;
                s += text[i++];
            }
            if (i >= n)
            {
                throw InputError
                (
                    fileName, syntaxEntry,
                    lineTag(startLine) + "string opened with '\"' is never closed"
                );
            }
            ++i;
            tokens.push_back({DictToken::Kind::string, s, startLine});
        }
        else if (isPunct(c))
        {
            tokens.push_back({DictToken::Kind::punct, std::string(1, c), line});
            ++i;
        }
        else
        {
            const std::size_t start = i;
            while
            (
                i < n
             && !std::isspace(static_cast<unsigned char>(text[i]))
             && !isPunct(text[i])
             && text[i] != '"'
             && !startsComment(i)
            )
            {
                ++i;
            }
            tokens.push_back({DictToken::Kind::word, text.substr(start, i - start), line});
        }
    }
    return tokens;
}

std::string lowerCase(std::string s)
{
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

//- The allowed word closest to a misspelt one, or "" if none is close.
std::string closest(const std::string& word, const std::vector<std::string>& allowed)
{
    std::string best;
    std::size_t bestDistance = 3;
    for (const std::string& a : allowed)
    {
        const std::size_t d = editDistance(lowerCase(word), lowerCase(a));
        if (d < bestDistance)
        {
            best = a;
            bestDistance = d;
        }
    }
    return best;
}

} // namespace


// * * * * * * * * * * * * * * * * Parser  * * * * * * * * * * * * * * * * //

//- Builds the Dictionary tree from the token list.
class DictionaryParser
{
public:
    DictionaryParser(std::vector<DictToken> tokens, const std::string& fileName)
    :
        tokens_(std::move(tokens)),
        fileName_(fileName)
    {}

    Dictionary parseTop()
    {
        Dictionary top(fileName_, "", 0);
        parseEntries(top, nullptr);

        const Dictionary::Entry* header = top.lookup("FoamFile");
        if (header && !header->dict)
        {
            syntaxError("FoamFile", header->line, "the FoamFile header must be a dictionary { ... }");
        }
        top.entries_.erase
        (
            std::remove_if
            (
                top.entries_.begin(), top.entries_.end(),
                [](const Dictionary::Entry& e) { return e.keyword == "FoamFile"; }
            ),
            top.entries_.end()
        );
        return top;
    }

private:
    [[noreturn]] void syntaxError(const std::string& entry, int line, const std::string& what) const
    {
        throw InputError(fileName_, entry.empty() ? "(top level)" : entry, lineTag(line) + what);
    }

    static std::string dotted(const std::string& parent, const std::string& key)
    {
        return parent.empty() ? key : parent + "." + key;
    }

    //- Entries up to the matching '}' (opening != nullptr) or to the end.
    void parseEntries(Dictionary& dict, const DictToken* opening)
    {
        while (true)
        {
            if (pos_ == tokens_.size())
            {
                if (opening)
                {
                    syntaxError
                    (
                        dict.path_, opening->line,
                        "'{' of '" + dict.path_ + "' is never closed by '}'"
                    );
                }
                return;
            }

            const DictToken& t = tokens_[pos_++];
            if (isPunct(t, '}'))
            {
                if (opening) return;
                syntaxError(dict.path_, t.line, "'}' without a matching '{'");
            }
            if (isPunct(t, ';'))
            {
                continue;   // stray ';' as in "name { ... };"
            }
            if (t.kind != DictToken::Kind::word)
            {
                syntaxError(dict.path_, t.line, "expected a keyword, found '" + render(t) + "'");
            }
            if (t.text[0] == '#' || t.text[0] == '$')
            {
                syntaxError
                (
                    dotted(dict.path_, t.text), t.line,
                    "directives (#...) and macros ($...) are not supported"
                );
            }
            if (const Dictionary::Entry* previous = dict.lookup(t.text))
            {
                syntaxError
                (
                    dotted(dict.path_, t.text), t.line,
                    "duplicate entry (first defined at line " + std::to_string(previous->line) + ")"
                );
            }

            Dictionary::Entry entry;
            entry.keyword = t.text;
            entry.line = t.line;
            if (pos_ < tokens_.size() && isPunct(tokens_[pos_], '{'))
            {
                const DictToken& brace = tokens_[pos_++];
                auto sub = std::make_shared<Dictionary>
                (
                    Dictionary(fileName_, dotted(dict.path_, t.text), brace.line)
                );
                parseEntries(*sub, &brace);
                entry.dict = std::move(sub);
            }
            else
            {
                entry.tokens = parseValue(dotted(dict.path_, t.text), t.line);
            }
            dict.entries_.push_back(std::move(entry));
        }
    }

    //- Tokens up to the ';' outside any brackets; brackets must balance.
    std::vector<DictToken> parseValue(const std::string& entryPath, int keywordLine)
    {
        std::vector<DictToken> value;
        std::vector<const DictToken*> open;
        while (true)
        {
            if (pos_ == tokens_.size())
            {
                if (!open.empty())
                {
                    syntaxError
                    (
                        entryPath, open.back()->line,
                        "'" + open.back()->text + "' is never closed"
                    );
                }
                syntaxError(entryPath, keywordLine, "missing ';' at the end of the entry");
            }
            const DictToken& t = tokens_[pos_];
            if (t.kind == DictToken::Kind::punct)
            {
                const char c = t.text[0];
                if (c == ';' && open.empty())
                {
                    ++pos_;
                    break;
                }
                if (c == '}' && open.empty())
                {
                    syntaxError(entryPath, t.line, "missing ';' before '}'");
                }
                if (c == '(' || c == '{')
                {
                    open.push_back(&t);
                }
                else if (c == ')' || c == '}')
                {
                    const char expected = open.empty() ? 0 : (open.back()->text[0] == '(' ? ')' : '}');
                    if (c != expected)
                    {
                        syntaxError
                        (
                            entryPath, t.line,
                            "'" + t.text + "' does not match "
                          + (open.empty() ? std::string("any opening bracket")
                                          : "'" + open.back()->text + "' of line "
                                          + std::to_string(open.back()->line))
                        );
                    }
                    open.pop_back();
                }
            }
            value.push_back(t);
            ++pos_;
        }
        if (value.empty())
        {
            syntaxError(entryPath, keywordLine, "entry has no value before ';'");
        }
        return value;
    }

    std::vector<DictToken> tokens_;
    std::string fileName_;
    std::size_t pos_ = 0;
};


// * * * * * * * * * * * * * * * * Dictionary * * * * * * * * * * * * * * * //

Dictionary::Dictionary(const std::string& fileName, const std::string& path, int line)
:
    fileName_(fileName),
    path_(path),
    line_(line)
{}


Dictionary Dictionary::readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        throw InputError(path, "(file)", "cannot open the file (missing or unreadable)");
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
    {
        throw InputError(path, "(file)", "error while reading the file");
    }
    return parse(text.str(), path);
}


Dictionary Dictionary::parse(const std::string& text, const std::string& fileName)
{
    return DictionaryParser(tokenise(text, fileName), fileName).parseTop();
}


std::string Dictionary::entryPath(const std::string& key) const
{
    return path_.empty() ? key : path_ + "." + key;
}


const Dictionary::Entry* Dictionary::lookup(const std::string& key) const
{
    for (const Entry& e : entries_)
    {
        if (e.keyword == key) return &e;
    }
    return nullptr;
}


bool Dictionary::found(const std::string& key) const
{
    return lookup(key) != nullptr;
}


bool Dictionary::isDict(const std::string& key) const
{
    const Entry* e = lookup(key);
    return e && e->dict;
}


std::vector<std::string> Dictionary::keys() const
{
    std::vector<std::string> result;
    for (const Entry& e : entries_) result.push_back(e.keyword);
    return result;
}


const Dictionary::Entry& Dictionary::entry(const std::string& key) const
{
    const Entry* e = lookup(key);
    if (!e) fail(key, "missing");
    return *e;
}


void Dictionary::fail(const std::string& key, const std::string& what) const
{
    const Entry* e = lookup(key);
    throw InputError(fileName_, entryPath(key), e ? lineTag(e->line) + what : what);
}


const Dictionary& Dictionary::subDict(const std::string& key) const
{
    const Entry* e = lookup(key);
    if (!e) fail(key, "missing; expected a sub-dictionary { ... }");
    if (!e->dict)
    {
        fail(key, "found '" + render(e->tokens) + "'; expected a sub-dictionary { ... }");
    }
    return *e->dict;
}


const DictToken& Dictionary::singleToken(const std::string& key, const std::string& expected) const
{
    const Entry* e = lookup(key);
    if (!e) fail(key, "missing; expected " + expected);
    if (e->dict) fail(key, "is a sub-dictionary; expected " + expected);

    const std::vector<DictToken>& v = e->tokens;
    if (v.size() != 1 || v[0].kind == DictToken::Kind::punct)
    {
        std::string hint;
        if (v.size() > 1 && v.back().line != v.front().line)
        {
            hint = " (missing ';' at line " + std::to_string(v.front().line) + "?)";
        }
        fail(key, "found '" + render(v) + "'; expected " + expected + hint);
    }
    return v[0];
}


double Dictionary::getScalar(const std::string& key) const
{
    const DictToken& t = singleToken(key, "a number");
    double value = 0;
    if (t.kind != DictToken::Kind::word || !toScalar(t.text, value))
    {
        fail(key, "'" + t.text + "' is not a number");
    }
    if (!std::isfinite(value))
    {
        fail(key, "'" + t.text + "' is not a finite number");
    }
    return value;
}


double Dictionary::getPositiveScalarOrDefault(const std::string& key, double def) const
{
    const double v = getScalarOrDefault(key, def);
    if (!(v > 0.0))
    {
        fail(key, "must be positive");
    }
    return v;
}


double Dictionary::getScalarOrDefault(const std::string& key, double def) const
{
    return found(key) ? getScalar(key) : def;
}


int Dictionary::getLabel(const std::string& key) const
{
    const DictToken& t = singleToken(key, "an integer");
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    if (first != last && *first == '+') ++first;

    int value = 0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (t.kind == DictToken::Kind::word && end == last && first != last)
    {
        if (ec == std::errc()) return value;
        if (ec == std::errc::result_out_of_range)
        {
            fail(key, "'" + t.text + "' is out of the integer range");
        }
    }
    double scalar = 0;
    if (t.kind == DictToken::Kind::word && toScalar(t.text, scalar))
    {
        fail(key, "'" + t.text + "' is not an integer; write a whole number without '.' or 'e'");
    }
    fail(key, "'" + t.text + "' is not an integer");
}


int Dictionary::getLabelOrDefault(const std::string& key, int def) const
{
    return found(key) ? getLabel(key) : def;
}


std::string Dictionary::getWord(const std::string& key) const
{
    const DictToken& t = singleToken(key, "a word");
    if (t.kind != DictToken::Kind::word)
    {
        fail(key, "found the quoted string " + render(t) + "; expected a word without quotes");
    }
    return t.text;
}


std::string Dictionary::getString(const std::string& key) const
{
    return singleToken(key, "a string").text;
}


std::string Dictionary::getChoice
(
    const std::string& key,
    const std::vector<std::string>& allowed
) const
{
    const std::string allowedText = "allowed: " + joined(allowed);
    const DictToken& t = singleToken(key, "one of the words " + joined(allowed));
    if
    (
        t.kind != DictToken::Kind::word
     || std::find(allowed.begin(), allowed.end(), t.text) == allowed.end()
    )
    {
        fail(key, "unknown value '" + t.text + "'; " + allowedText);
    }
    return t.text;
}


std::string Dictionary::getChoiceOrDefault
(
    const std::string& key,
    const std::vector<std::string>& allowed,
    const std::string& def
) const
{
    return found(key) ? getChoice(key, allowed) : def;
}


bool Dictionary::getBool(const std::string& key) const
{
    const DictToken& t = singleToken(key, "true/false, yes/no or on/off");
    if (t.kind == DictToken::Kind::word)
    {
        if (t.text == "true" || t.text == "yes" || t.text == "on") return true;
        if (t.text == "false" || t.text == "no" || t.text == "off") return false;
    }
    fail(key, "'" + t.text + "' is not a boolean; allowed: true false yes no on off");
}


bool Dictionary::getBoolOrDefault(const std::string& key, bool def) const
{
    return found(key) ? getBool(key) : def;
}


std::vector<double> Dictionary::getScalarList(const std::string& key) const
{
    const std::string expected = "a list of numbers such as (1 2 3)";
    const Entry* e = lookup(key);
    if (!e) fail(key, "missing; expected " + expected);
    if (e->dict) fail(key, "is a sub-dictionary; expected " + expected);

    const std::vector<DictToken>& v = e->tokens;
    std::size_t first = 0;
    bool sized = false;
    double size = 0;
    if (!v.empty() && v[0].kind == DictToken::Kind::word && v.size() > 1 && isPunct(v[1], '('))
    {
        sized = toScalar(v[0].text, size);
        first = 1;
    }
    if
    (
        v.size() < first + 2 || !isPunct(v[first], '(') || !isPunct(v.back(), ')')
     || (first == 1 && !sized)
    )
    {
        fail(key, "found '" + render(v) + "'; expected " + expected);
    }

    std::vector<double> values;
    for (std::size_t i = first + 1; i + 1 < v.size(); ++i)
    {
        double x = 0;
        if (v[i].kind != DictToken::Kind::word || !toScalar(v[i].text, x))
        {
            fail(key, "list element '" + render(v[i]) + "' is not a number");
        }
        if (!std::isfinite(x))
        {
            fail(key, "list element '" + v[i].text + "' is not a finite number");
        }
        values.push_back(x);
    }
    if (sized && size != static_cast<double>(values.size()))
    {
        fail
        (
            key,
            "list size prefix " + v[0].text + " does not match its "
          + std::to_string(values.size()) + " elements"
        );
    }
    return values;
}


void Dictionary::checkKeys(const std::vector<std::string>& allowed) const
{
    for (const Entry& e : entries_)
    {
        if (std::find(allowed.begin(), allowed.end(), e.keyword) != allowed.end()) continue;

        const std::string suggestion = closest(e.keyword, allowed);
        fail
        (
            e.keyword,
            "unknown keyword"
          + (suggestion.empty() ? std::string() : " (did you mean '" + suggestion + "'?)")
          + "; allowed: " + joined(allowed)
        );
    }
}

} // namespace iceDEM
