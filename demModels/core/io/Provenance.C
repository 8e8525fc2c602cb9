#include "Provenance.H"

#include "Dictionary.H"
#include "InputError.H"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace iceDEM
{

namespace
{

std::string tokensText(const Dictionary::Entry& e)
{
    std::string text;
    for (const DictToken& t : e.tokens)
    {
        text += (text.empty() ? "" : " ")
            + (t.kind == DictToken::Kind::string ? "\"" + t.text + "\"" : t.text);
    }
    return text;
}


//- Entries named "<label>/<dotted path in the file>" (a sub-dictionary's
//  own path included, so that "label/test.speed" reads the same whether the
//  whole file or its `test` was added).
void flatten
(
    std::map<std::string, std::string>& out,
    const std::string& label,
    const Dictionary& d,
    const std::set<std::string>& ignored,
    bool topLevel = true
)
{
    for (const std::string& key : d.keys())
    {
        // a keyword of d itself, or an entry anywhere by its dotted path (blocks.shape)
        if ((topLevel && ignored.count(key)) || ignored.count(d.entryPath(key))) continue;
        const Dictionary::Entry& e = d.entry(key);
        if (e.dict)
        {
            flatten(out, label, *e.dict, ignored, false);
        }
        else
        {
            out[label + "/" + d.entryPath(key)] = tokensText(e);
        }
    }
}

} // namespace


std::string fnv1aHex(const std::string& text)
{
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : text)
    {
        h ^= c;
        h *= 0x100000001b3ULL;
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}


void Provenance::add(const std::string& name, const std::string& value)
{
    inputs_[name] = value;
}


void Provenance::addDictionary
(
    const std::string& label,
    const Dictionary& d,
    const std::set<std::string>& ignored
)
{
    flatten(inputs_, label, d, ignored);
}


void Provenance::addDictionaryFile
(
    const std::string& label,
    const std::string& path,
    const std::set<std::string>& ignored
)
{
    addDictionary(label, Dictionary::readFile(path), ignored);
}


void Provenance::addFileContent(const std::string& label, const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        throw InputError(path, "(file)", "cannot be read");
    }
    std::ostringstream content;
    content << in.rdbuf();
    add(label, "content " + fnv1aHex(content.str()));
}


std::string Provenance::value(const std::string& name) const
{
    const auto it = inputs_.find(name);
    return it == inputs_.end() ? "" : it->second;
}


void Provenance::addStage(const std::string& label, const Provenance& stage)
{
    add(label, stage.empty() ? "unknown" : "fingerprint " + stage.fingerprint());
}


std::string Provenance::fingerprint() const
{
    return fnv1aHex(text());
}


std::string Provenance::text() const
{
    std::string text;
    for (const auto& [name, value] : inputs_)
    {
        text += name + " = " + value + "\n";
    }
    return text;
}


Provenance Provenance::fromText(const std::string& text)
{
    Provenance p;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line))
    {
        const std::size_t sep = line.find(" = ");
        if (sep != std::string::npos)
        {
            p.inputs_[line.substr(0, sep)] = line.substr(sep + 3);
        }
    }
    return p;
}


std::vector<std::string> Provenance::differences(const Provenance& now) const
{
    std::vector<std::string> lines;
    auto quoted = [](const std::map<std::string, std::string>& m, const std::string& key)
    {
        const auto it = m.find(key);
        return it == m.end() ? std::string("absent") : "'" + it->second + "'";
    };
    std::set<std::string> names;
    for (const auto& [name, value] : inputs_) names.insert(name);
    for (const auto& [name, value] : now.inputs_) names.insert(name);
    for (const std::string& name : names)
    {
        const std::string before = quoted(inputs_, name), after = quoted(now.inputs_, name);
        if (before != after)
        {
            lines.push_back(name + ": " + before + " when it was made, " + after + " now");
        }
    }
    return lines;
}


void requireSameInputs
(
    const Provenance& stored,
    const Provenance& now,
    const std::string& file,
    const std::string& rebuildCommand
)
{
    if (stored.empty())
    {
        throw InputError(file, "inputs", "holds no record of the inputs it was made from (an older "
            "version wrote it, or another program): make it anew with `" + rebuildCommand + "`");
    }
    const std::vector<std::string> changed = stored.differences(now);
    if (changed.empty())
    {
        return;
    }
    std::string list;
    const std::size_t shown = std::min<std::size_t>(changed.size(), 12);
    for (std::size_t k = 0; k < shown; ++k) list += "\n      " + changed[k];
    if (changed.size() > shown) list += "\n      ... and " + std::to_string(changed.size() - shown) + " more";
    throw InputError(file, "inputs",
        "was made from other inputs than the case has now (" + std::to_string(changed.size())
      + " differ):" + list + "\n    make it anew with `" + rebuildCommand + "`, or put the inputs back");
}

} // namespace iceDEM
