#include "VtkWriter.H"

#include "AtomicFile.H"
#include "VtkCompressedBlocks.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace iceDEM
{

namespace
{

void appendNumber(std::string& text, double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.10g", value);
    text += buffer;
}

void appendNumber(std::string& text, long value)
{
    text += std::to_string(value);
}

void appendNumber(std::string& text, int value)
{
    text += std::to_string(value);
}

std::string xmlEscape(const std::string& raw)
{
    std::string escaped;
    for (char c : raw)
    {
        switch (c)
        {
            case '&': escaped += "&amp;"; break;
            case '<': escaped += "&lt;"; break;
            case '>': escaped += "&gt;"; break;
            case '"': escaped += "&quot;"; break;
            case '\'': escaped += "&apos;"; break;
            default: escaped += c;
        }
    }
    return escaped;
}

std::string xmlUnescape(const std::string& escaped)
{
    static const std::pair<const char*, char> entities[] =
        {{"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    std::string raw;
    for (std::size_t i = 0; i < escaped.size();)
    {
        bool replaced = false;
        for (const auto& [entity, c] : entities)
        {
            if (escaped.compare(i, std::char_traits<char>::length(entity), entity) == 0)
            {
                raw += c;
                i += std::char_traits<char>::length(entity);
                replaced = true;
                break;
            }
        }
        if (!replaced)
        {
            raw += escaped[i++];
        }
    }
    return raw;
}


template<class Container>
void checkLength
(
    const Container& values,
    std::size_t expected,
    const char* name,
    const char* owner
)
{
    if (!values.empty() && values.size() != expected)
    {
        throw std::invalid_argument
        (
            std::string(owner) + ": array '" + name + "' has " + std::to_string(values.size())
          + " entries, expected " + std::to_string(expected) + " (or none)"
        );
    }
}


//- One .vtp file's XML and, in binary, the arrays' bytes appended after it.
struct VtpContents
{
    explicit VtpContents(VtkFormat f)
    :
        format(f)
    {}

    VtkFormat format;
    std::string xml;
    std::string appended;
};


//- Appends <DataArray> elements; empty arrays are left out.
class ArrayWriter
{
public:
    //- keepEmpty: write empty arrays too (points and cell connectivity of an empty piece).
    explicit ArrayWriter(VtpContents& file, bool keepEmpty = false)
    :
        file_(file),
        keepEmpty_(keepEmpty)
    {}

    void scalars(const char* name, const std::vector<double>& values)
    {
        write(name, "Float64", 1, values,
              [](const double& v, std::string& t) { appendNumber(t, v); });
    }

    void scalars(const char* name, const std::vector<long>& values)
    {
        write(name, "Int64", 1, values,
              [](const long& v, std::string& t) { appendNumber(t, v); });
    }

    void scalars(const char* name, const std::vector<int>& values)
    {
        write(name, "Int32", 1, values,
              [](const int& v, std::string& t) { appendNumber(t, v); });
    }

    void vectors(const char* name, const std::vector<Vec3>& values)
    {
        write
        (
            name, "Float64", 3, values,
            [](const Vec3& v, std::string& t)
            {
                appendNumber(t, v.x());
                t += ' ';
                appendNumber(t, v.y());
                t += ' ';
                appendNumber(t, v.z());
            }
        );
    }

private:
    template<class T, class Append>
    void write
    (
        const char* name,
        const char* type,
        int components,
        const std::vector<T>& values,
        Append append
    )
    {
        if (values.empty() && !keepEmpty_)
        {
            return;
        }
        std::string& text = file_.xml;
        text += "        <DataArray type=\"";
        text += type;
        text += "\" Name=\"";
        text += name;
        text += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"";
        if (file_.format == VtkFormat::binary)
        {
            text += "appended\" offset=\"" + std::to_string(file_.appended.size()) + "\"/>\n";
            appendVtkCompressedBlocks(file_.appended, values.data(), values.size()*sizeof(T));
            return;
        }
        text += "ascii\">\n";
        for (std::size_t i = 0; i < values.size(); ++i)
        {
            text += (i % 4 == 0) ? "          " : " ";
            append(values[i], text);
            if (i % 4 == 3 || i + 1 == values.size())
            {
                text += '\n';
            }
        }
        text += "        </DataArray>\n";
    }

    VtpContents& file_;
    bool keepEmpty_;
};

static_assert(sizeof(Vec3) == 3*sizeof(double) && sizeof(long) == 8 && sizeof(int) == 4,
              "binary arrays are the vectors' own bytes: Float64 x 3, Int64, Int32");


// Cells of n points each: the offsets array.
std::vector<long> offsetsOfCells(std::size_t nCells, int n)
{
    std::vector<long> offsets(nCells);
    for (std::size_t c = 0; c < nCells; ++c)
    {
        offsets[c] = static_cast<long>((c + 1)*n);
    }
    return offsets;
}


void appendCells
(
    VtpContents& file,
    const char* section,
    const std::vector<long>& connectivity,
    const std::vector<long>& offsets
)
{
    file.xml += "      <";
    file.xml += section;
    file.xml += ">\n";
    ArrayWriter arrays(file, true);
    arrays.scalars("connectivity", connectivity);
    arrays.scalars("offsets", offsets);
    file.xml += "      </";
    file.xml += section;
    file.xml += ">\n";
}


// Cells of n points each, numbered consecutively: connectivity and offsets arrays.
void appendConsecutiveCells(VtpContents& file, const char* section, std::size_t nCells, int n)
{
    std::vector<long> connectivity(nCells*n);
    for (std::size_t i = 0; i < connectivity.size(); ++i)
    {
        connectivity[i] = static_cast<long>(i);
    }
    appendCells(file, section, connectivity, offsetsOfCells(nCells, n));
}


void appendPieceHeader
(
    VtpContents& file,
    std::size_t nPoints,
    std::size_t nVerts,
    std::size_t nLines
)
{
    file.xml +=
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\"";
    if (file.format == VtkFormat::binary)
    {
        file.xml += " compressor=\"vtkZLibDataCompressor\"";
    }
    file.xml +=
        ">\n"
        "  <PolyData>\n"
        "    <Piece NumberOfPoints=\"" + std::to_string(nPoints)
      + "\" NumberOfVerts=\"" + std::to_string(nVerts)
      + "\" NumberOfLines=\"" + std::to_string(nLines)
      + "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
}


std::string finished(VtpContents& file)
{
    file.xml +=
        "    </Piece>\n"
        "  </PolyData>\n";
    if (file.format == VtkFormat::binary)
    {
        // Raw bytes after the underscore, up to the closing tag (VTK's "raw" encoding).
        file.xml += "  <AppendedData encoding=\"raw\">\n   _";
        file.xml += file.appended;
        file.xml += "\n  </AppendedData>\n";
    }
    file.xml += "</VTKFile>\n";
    return std::move(file.xml);
}


void appendPoints(VtpContents& file, const std::vector<Vec3>& points)
{
    file.xml += "      <Points>\n";
    ArrayWriter(file, true).vectors("Points", points);
    file.xml += "      </Points>\n";
}


fs::path folderOf(const std::string& path)
{
    const fs::path parent = fs::absolute(fs::path(path)).parent_path();
    return parent;
}


std::string attribute(const std::string& element, const std::string& name)
{
    const std::string key = " " + name + "=\"";
    const std::size_t start = element.find(key);
    if (start == std::string::npos)
    {
        return {};
    }
    const std::size_t valueStart = start + key.size();
    const std::size_t end = element.find('"', valueStart);
    if (end == std::string::npos)
    {
        return {};
    }
    return xmlUnescape(element.substr(valueStart, end - valueStart));
}

} // namespace


std::string particlesVtp(const ParticleFrame& frame, VtkFormat format)
{
    const std::size_t n = frame.position.size();
    const char* owner = "writeParticlesVtp";
    checkLength(frame.velocity, n, "velocity", owner);
    checkLength(frame.force, n, "force", owner);
    checkLength(frame.radius, n, "radius", owner);
    checkLength(frame.tag, n, "tag", owner);
    checkLength(frame.bondCount, n, "bondCount", owner);
    checkLength(frame.fixed, n, "fixed", owner);
    checkLength(frame.block, n, "block", owner);

    VtpContents file(format);
    appendPieceHeader(file, n, n, 0);
    file.xml += "      <PointData";
    if (n > 0 && !frame.radius.empty())
    {
        file.xml += " Scalars=\"radius\"";
    }
    if (n > 0 && !frame.velocity.empty())
    {
        file.xml += " Vectors=\"velocity\"";
    }
    file.xml += ">\n";
    ArrayWriter arrays(file);
    arrays.scalars("radius", frame.radius);
    arrays.vectors("velocity", frame.velocity);
    arrays.vectors("force", frame.force);
    arrays.scalars("tag", frame.tag);
    arrays.scalars("bondCount", frame.bondCount);
    arrays.scalars("fixed", frame.fixed);
    arrays.scalars("block", frame.block);
    file.xml += "      </PointData>\n";
    file.xml += "      <CellData>\n      </CellData>\n";
    appendPoints(file, frame.position);
    appendConsecutiveCells(file, "Verts", n, 1);
    return finished(file);
}


std::string bondsVtp(const BondFrame& frame, VtkFormat format)
{
    const std::size_t n = frame.ends.size();
    const char* owner = "writeBondsVtp";
    checkLength(frame.family, n, "family", owner);
    checkLength(frame.state, n, "state", owner);
    checkLength(frame.mode, n, "mode", owner);
    checkLength(frame.time, n, "breakTime", owner);
    for (const auto& ends : frame.ends)
    {
        for (const long end : ends)
        {
            if (end < 0 || end >= static_cast<long>(frame.points.size()))
            {
                throw std::invalid_argument
                (
                    std::string(owner) + ": a bond ends at point " + std::to_string(end) + " of "
                  + std::to_string(frame.points.size())
                );
            }
        }
    }

    // ascii: both ends of every bond written again (the files as they always were).
    std::vector<Vec3> ownEnds;
    if (format == VtkFormat::ascii)
    {
        ownEnds.reserve(2*n);
        for (const auto& [a, b] : frame.ends)
        {
            ownEnds.push_back(frame.points[a]);
            ownEnds.push_back(frame.points[b]);
        }
    }
    const std::vector<Vec3>& points = format == VtkFormat::ascii ? ownEnds : frame.points;

    VtpContents file(format);
    appendPieceHeader(file, points.size(), 0, n);
    file.xml += "      <PointData>\n      </PointData>\n";
    file.xml += "      <CellData";
    if (n > 0 && !frame.state.empty())
    {
        file.xml += " Scalars=\"state\"";
    }
    file.xml += ">\n";
    ArrayWriter arrays(file);
    arrays.scalars("family", frame.family);
    arrays.scalars("state", frame.state);
    arrays.scalars("mode", frame.mode);
    arrays.scalars("breakTime", frame.time);
    file.xml += "      </CellData>\n";
    appendPoints(file, points);
    if (format == VtkFormat::ascii)
    {
        appendConsecutiveCells(file, "Lines", n, 2);
    }
    else
    {
        std::vector<long> connectivity;
        connectivity.reserve(2*n);
        for (const auto& [a, b] : frame.ends)
        {
            connectivity.push_back(a);
            connectivity.push_back(b);
        }
        appendCells(file, "Lines", connectivity, offsetsOfCells(n, 2));
    }
    return finished(file);
}


void writeParticlesVtp(const std::string& path, const ParticleFrame& frame, VtkFormat format)
{
    writeFileAtomically(path, particlesVtp(frame, format));
}


void writeBondsVtp(const std::string& path, const BondFrame& frame, VtkFormat format)
{
    writeFileAtomically(path, bondsVtp(frame, format));
}


PvdCollection::PvdCollection(std::string path)
:
    path_(std::move(path))
{}


PvdCollection PvdCollection::read(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
    {
        throw std::runtime_error("cannot read ParaView collection '" + path + "'");
    }
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    if (text.find("type=\"Collection\"") == std::string::npos
     || text.find("</VTKFile>") == std::string::npos)
    {
        throw std::runtime_error("'" + path + "' is not a complete ParaView collection");
    }

    PvdCollection collection(path);
    for (std::size_t start = text.find("<DataSet"); start != std::string::npos;
         start = text.find("<DataSet", start + 1))
    {
        const std::size_t end = text.find("/>", start);
        if (end == std::string::npos)
        {
            throw std::runtime_error("'" + path + "': unterminated DataSet element");
        }
        const std::string element = text.substr(start, end - start);
        const std::string time = attribute(element, "timestep");
        const std::string part = attribute(element, "part");
        const std::string file = attribute(element, "file");
        try
        {
            collection.entries_.push_back
            (
                {std::stod(time), part.empty() ? 0 : std::stoi(part), file}
            );
        }
        catch (const std::exception&)
        {
            throw std::runtime_error("'" + path + "': bad DataSet element '" + element + "'");
        }
    }
    return collection;
}


void PvdCollection::add(double time, const std::string& file, int part)
{
    if (!std::isfinite(time))
    {
        throw std::invalid_argument("PvdCollection '" + path_ + "': non-finite time");
    }
    std::string stored = file;
    if (fs::path(file).is_absolute())
    {
        const fs::path relative = fs::path(file).lexically_relative(folderOf(path_));
        if (!relative.empty())
        {
            stored = relative.generic_string();
        }
    }

    const auto before = [](const Entry& e, double t, int p)
    {
        return e.time < t || (e.time == t && e.part < p);
    };
    auto position = std::find_if
    (
        entries_.begin(), entries_.end(),
        [&](const Entry& e) { return !before(e, time, part); }
    );
    if (position != entries_.end() && position->time == time && position->part == part)
    {
        position->file = stored;
    }
    else
    {
        entries_.insert(position, Entry{time, part, stored});
    }
    write();
}


void PvdCollection::removeAfter(double time)
{
    entries_.erase
    (
        std::remove_if(entries_.begin(), entries_.end(),
                       [time](const Entry& e) { return e.time > time; }),
        entries_.end()
    );
    write();
}


std::string PvdCollection::text() const
{
    std::string text =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        "  <Collection>\n";
    for (const Entry& e : entries_)
    {
        char time[32];
        std::snprintf(time, sizeof(time), "%.12g", e.time);
        text += "    <DataSet timestep=\"";
        text += time;
        text += "\" group=\"\" part=\"" + std::to_string(e.part) + "\" file=\""
              + xmlEscape(e.file) + "\"/>\n";
    }
    text += "  </Collection>\n</VTKFile>\n";
    return text;
}


void PvdCollection::write() const
{
    writeFileAtomically(path_, text());
}

} // namespace iceDEM
