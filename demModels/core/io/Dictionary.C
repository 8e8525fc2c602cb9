#include "Dictionary.H"
#include "InputError.H"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
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
        else if (c == '$' && i + 1 < n && text[i + 1] == '{')
        {
            const std::size_t close = text.find('}', i);
            if (close == std::string::npos || text.find('\n', i) < close)
            {
                throw InputError
                (
                    fileName, syntaxEntry, lineTag(line) + "'${' is not closed by '}' on its line"
                );
            }
            tokens.push_back({DictToken::Kind::word, "$" + text.substr(i + 2, close - i - 2), line});
            i = close + 1;
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

//- The whole text of a regular file; false if it cannot be read.
bool readText(const std::string& path, std::string& text)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (!in || in.bad()) return false;
    text = buffer.str();
    return true;
}

//- Where `#include "written"` in file includer points: an absolute path as
//  written, a relative one relative to the includer's directory.
std::string includePath(const std::string& includer, const std::string& written)
{
    const std::filesystem::path target(written);
    if (target.is_absolute()) return target.lexically_normal().string();
    return (std::filesystem::path(includer).parent_path() / target).lexically_normal().string();
}

//- A file's canonical path (to recognise it when included again), or the
//  path itself when it cannot be resolved.
std::string fileIdentity(const std::string& path)
{
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
    return ec ? path : canonical.string();
}

std::vector<std::string> split(const std::string& text, char separator)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true)
    {
        const std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string::npos) return parts;
        start = end + 1;
    }
}

//- The entry that $name names, nullptr if none. scopes: the dictionaries
//  enclosing the use, outermost first. As OpenFOAM: `a` is looked up from
//  the innermost scope outward; `a.b.c` finds `a` so and descends; `:a.b`
//  (or `^a.b`) starts at the top level; each dot beyond the first of a
//  leading `..a` goes up one level; `/a/b`, `../a` and `a/b` are the
//  slash-separated forms.
const Dictionary::Entry* findVariable
(
    const std::vector<const Dictionary*>& scopes,
    std::string name
)
{
    std::size_t level = scopes.size() - 1;
    bool outward = true;
    const char separator = name.find('/') != std::string::npos ? '/' : '.';
    if (name[0] == ':' || name[0] == '^' || (separator == '/' && name[0] == '/'))
    {
        level = 0;
        outward = false;
        name.erase(0, 1);
    }
    else if (separator == '.' && name[0] == '.')
    {
        const std::size_t dots = name.find_first_not_of('.');
        if (dots == std::string::npos || dots - 1 > level) return nullptr;
        level -= dots - 1;
        outward = false;
        name.erase(0, dots);
    }

    std::vector<std::string> parts = split(name, separator);
    while (separator == '/' && !parts.empty() && (parts[0] == "." || parts[0] == ".."))
    {
        if (parts[0] == "..")
        {
            if (level == 0) return nullptr;
            --level;
        }
        outward = false;
        parts.erase(parts.begin());
    }
    if (parts.empty()) return nullptr;

    const Dictionary::Entry* found = nullptr;
    for (std::size_t l = level + 1; l-- > 0 && !found; )
    {
        if (scopes[l]->found(parts[0])) found = &scopes[l]->entry(parts[0]);
        if (!outward) break;
    }
    for (std::size_t i = 1; i < parts.size() && found; ++i)
    {
        const bool descends = found->dict && found->dict->found(parts[i]);
        found = descends ? &found->dict->entry(parts[i]) : nullptr;
    }
    return found;
}

} // namespace


// * * * * * * * * * * * * * * * * Parser  * * * * * * * * * * * * * * * * //

//- Builds the Dictionary tree from the tokens of one file; an #include hands
//  the included file to a nested parser that adds to the same dictionary.
class DictionaryParser
{
public:
    //- Dictionaries enclosing the one being read, outermost first, it last:
    //  where a $variable is looked up.
    using Scopes = std::vector<const Dictionary*>;

    DictionaryParser
    (
        const std::string& text,
        const std::string& fileName,
        std::vector<std::string> includeChain
    )
    :
        tokens_(tokenise(text, fileName)),
        fileName_(fileName),
        includeChain_(std::move(includeChain))
    {}

    Dictionary parseTop()
    {
        Dictionary top(fileName_, "", 0);
        Scopes scopes{&top};
        parseEntries(top, nullptr, scopes);
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

    //- Entries up to the matching '}' (opening != nullptr) or to the end of
    //  the file (the file's top level, which may be a sub-dictionary that
    //  includes it).
    void parseEntries(Dictionary& dict, const DictToken* opening, Scopes& scopes)
    {
        std::map<std::string, int> writtenHere;   // keyword -> line, for duplicates
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
                continue;   // stray ';' as in "name { ... };" or "#include "f";"
            }
            if (t.kind != DictToken::Kind::word)
            {
                syntaxError(dict.path_, t.line, "expected a keyword, found '" + render(t) + "'");
            }
            if (t.text[0] == '#')
            {
                parseDirective(dict, t, scopes);
                continue;
            }
            if (t.text.size() > 1 && t.text[0] == '$')
            {
                mergeNamedDict(dict, t, scopes);
                continue;
            }

            const auto [first, isNew] = writtenHere.emplace(t.text, t.line);
            if (!isNew)
            {
                syntaxError
                (
                    dotted(dict.path_, t.text), t.line,
                    "duplicate entry (first defined at line " + std::to_string(first->second) + ")"
                );
            }

            Dictionary::Entry entry = parseEntry(dict, t, scopes);
            if (!opening && entry.keyword == "FoamFile")
            {
                if (!entry.dict)
                {
                    syntaxError("FoamFile", t.line, "the FoamFile header must be a dictionary { ... }");
                }
                continue;   // the header of this file, not content
            }
            addEntry(dict, std::move(entry));
        }
    }

    //- The entry whose keyword is t: a sub-dictionary or a value.
    Dictionary::Entry parseEntry(const Dictionary& dict, const DictToken& t, Scopes& scopes)
    {
        Dictionary::Entry entry;
        entry.keyword = t.text;
        entry.fileName = fileName_;
        entry.line = t.line;
        const std::string path = dotted(dict.path_, t.text);
        if (pos_ < tokens_.size() && isPunct(tokens_[pos_], '{'))
        {
            const DictToken& brace = tokens_[pos_++];
            auto sub = std::make_shared<Dictionary>(Dictionary(fileName_, path, brace.line));
            scopes.push_back(sub.get());
            parseEntries(*sub, &brace, scopes);
            scopes.pop_back();
            entry.dict = std::move(sub);
            return entry;
        }

        entry.tokens = expandVariables(parseValue(path, t.line), path, scopes);
        return entry;
    }

    //- OpenFOAM's merge rule: a new sub-dictionary merges into an existing
    //  one of the same keyword; anything else replaces the existing entry
    //  where it stands.
    static void addEntry(Dictionary& dict, Dictionary::Entry entry)
    {
        auto existing = std::find_if
        (
            dict.entries_.begin(), dict.entries_.end(),
            [&](const Dictionary::Entry& e) { return e.keyword == entry.keyword; }
        );
        if (existing == dict.entries_.end())
        {
            dict.entries_.push_back(std::move(entry));
        }
        else if (existing->dict && entry.dict)
        {
            auto merged = std::make_shared<Dictionary>(*existing->dict);
            for (const Dictionary::Entry& e : entry.dict->entries_)
            {
                addEntry(*merged, e);
            }
            existing->dict = std::move(merged);
        }
        else
        {
            *existing = std::move(entry);
        }
    }

    //- A copy of src whose entries carry the dotted paths under `path`.
    static std::shared_ptr<const Dictionary> relocated(const Dictionary& src, const std::string& path)
    {
        auto copy = std::make_shared<Dictionary>(src);
        copy->path_ = path;
        for (Dictionary::Entry& e : copy->entries_)
        {
            if (e.dict) e.dict = relocated(*e.dict, dotted(path, e.keyword));
        }
        return copy;
    }

    // * * * * * * * * * * * * * * * Includes * * * * * * * * * * * * * * * //

    void parseDirective(Dictionary& dict, const DictToken& directive, Scopes& scopes)
    {
        const std::string entry = dotted(dict.path_, directive.text);
        const bool optional = directive.text == "#includeIfPresent";
        if (directive.text != "#include" && !optional)
        {
            syntaxError
            (
                entry, directive.line,
                "directive '" + directive.text
              + "' is not supported (only #include and #includeIfPresent are)"
            );
        }
        if (pos_ == tokens_.size() || tokens_[pos_].kind == DictToken::Kind::punct)
        {
            syntaxError(entry, directive.line, directive.text + " needs a file name such as \"file\"");
        }
        const std::string written = tokens_[pos_++].text;
        const std::string path = includePath(fileName_, written);

        const std::string identity = fileIdentity(path);
        if (std::find(includeChain_.begin(), includeChain_.end(), identity) != includeChain_.end())
        {
            syntaxError
            (
                entry, directive.line,
                "include cycle: '" + path + "' is already being read (" + chainText(path) + ")"
            );
        }

        std::string text;
        if (!readText(path, text))
        {
            if (optional) return;
            syntaxError
            (
                entry, directive.line,
                "cannot open the included file \"" + written + "\" (tried '" + path + "')"
            );
        }

        std::vector<std::string> chain = includeChain_;
        chain.push_back(identity);
        DictionaryParser included(text, path, std::move(chain));
        included.parseEntries(dict, nullptr, scopes);
    }

    //- The include chain of this file, and path, as "a -> b -> path".
    std::string chainText(const std::string& path) const
    {
        std::string s;
        for (const std::string& f : includeChain_) s += f + " -> ";
        return s + fileIdentity(path);
    }

    // * * * * * * * * * * * * * * Variables * * * * * * * * * * * * * * * //

    //- `$sub;` as an entry: the entries of sub-dictionary sub merged in here.
    void mergeNamedDict(Dictionary& dict, const DictToken& t, const Scopes& scopes)
    {
        const std::string name = t.text.substr(1);
        const Dictionary::Entry* found = findVariable(scopes, name);
        if (!found)
        {
            syntaxError(dotted(dict.path_, t.text), t.line, "undefined variable '" + t.text + "'");
        }
        if (!found->dict)
        {
            syntaxError
            (
                dotted(dict.path_, t.text), t.line,
                "'" + t.text + "' is not a sub-dictionary; `$name;` as an entry"
                " copies the entries of a sub-dictionary"
            );
        }
        const std::shared_ptr<const Dictionary> copy = relocated(*found->dict, dict.path_);
        for (const Dictionary::Entry& e : copy->entries_)
        {
            addEntry(dict, e);
        }
    }

    //- Each `$name` token replaced by the value of entry name (or of the
    //  environment variable name when no entry has it).
    std::vector<DictToken> expandVariables
    (
        const std::vector<DictToken>& raw,
        const std::string& entryPath,
        const Scopes& scopes
    ) const
    {
        std::vector<DictToken> result;
        for (const DictToken& t : raw)
        {
            if (t.kind != DictToken::Kind::word || t.text.size() < 2 || t.text[0] != '$')
            {
                result.push_back(t);
                continue;
            }
            const std::string name = t.text.substr(1);
            const Dictionary::Entry* found = findVariable(scopes, name);
            if (found && found->dict)
            {
                // OpenFOAM would paste the dictionary's entries as loose tokens here.
                syntaxError
                (
                    entryPath, t.line,
                    "'" + t.text + "' is a sub-dictionary; copy it with `"
                  + entryPath.substr(entryPath.rfind('.') + 1) + " { " + t.text + "; }`"
                );
            }
            std::vector<DictToken> replacement;
            if (found)
            {
                replacement = found->tokens;
            }
            else if (const char* env = std::getenv(name.c_str()); env && *env)
            {
                replacement = tokenise(env, "environment variable " + name);
            }
            else
            {
                syntaxError
                (
                    entryPath, t.line,
                    "undefined variable '" + t.text + "' (no entry '" + name
                  + "' above it in this dictionary or an enclosing one)"
                );
            }
            for (DictToken r : replacement)
            {
                r.line = t.line;   // messages point at the use
                result.push_back(std::move(r));
            }
        }
        return result;
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
    std::vector<std::string> includeChain_;   // files being read, outermost first
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
    std::string text;
    if (!readText(path, text))
    {
        throw InputError(path, "(file)", "cannot open the file (missing or unreadable)");
    }
    return DictionaryParser(text, path, {fileIdentity(path)}).parseTop();
}


Dictionary Dictionary::parse(const std::string& text, const std::string& fileName)
{
    return DictionaryParser(text, fileName, {fileIdentity(fileName)}).parseTop();
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
    if (!e) throw InputError(fileName_, entryPath(key), what);
    throw InputError(e->fileName, entryPath(key), lineTag(e->line) + what);
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
