#include "InputError.H"
#include "VtkWriter.H"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace iceDEM;

namespace
{

// A minimal XML reader, enough to check that the files are well formed (every element
// closed by its own end tag, quoted attributes, one root) and to read them back.
struct XmlElement
{
    std::string name;
    std::map<std::string, std::string> attributes;
    std::string text;
    std::vector<XmlElement> children;

    const XmlElement& child(const std::string& childName) const
    {
        for (const XmlElement& c : children)
        {
            if (c.name == childName)
            {
                return c;
            }
        }
        throw std::runtime_error("<" + name + "> has no <" + childName + ">");
    }

    const XmlElement& array(const std::string& arrayName) const
    {
        for (const XmlElement& c : children)
        {
            if (c.name == "DataArray" && c.attributes.count("Name")
             && c.attributes.at("Name") == arrayName)
            {
                return c;
            }
        }
        throw std::runtime_error("<" + name + "> has no DataArray " + arrayName);
    }

    std::vector<double> values() const
    {
        std::istringstream in(text);
        std::vector<double> v;
        std::string token;
        while (in >> token)
        {
            v.push_back(std::stod(token));
        }
        return v;
    }
};

class XmlReader
{
public:
    explicit XmlReader(std::string text)
    :
        text_(std::move(text))
    {}

    XmlElement document()
    {
        skipSpace();
        if (text_.compare(pos_, 5, "<?xml") == 0)
        {
            pos_ = text_.find("?>", pos_);
            expect(pos_ != std::string::npos, "unterminated prolog");
            pos_ += 2;
        }
        skipSpace();
        XmlElement root = element();
        skipSpace();
        expect(pos_ == text_.size(), "content after the root element");
        return root;
    }

private:
    void expect(bool condition, const std::string& what) const
    {
        if (!condition)
        {
            throw std::runtime_error("malformed XML at " + std::to_string(pos_) + ": " + what);
        }
    }

    void skipSpace()
    {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])))
        {
            ++pos_;
        }
    }

    std::string name()
    {
        const std::size_t start = pos_;
        while (pos_ < text_.size()
            && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_'))
        {
            ++pos_;
        }
        expect(pos_ > start, "expected a name");
        return text_.substr(start, pos_ - start);
    }

    XmlElement element()
    {
        expect(text_[pos_] == '<', "expected '<'");
        ++pos_;
        XmlElement e;
        e.name = name();
        for (;;)
        {
            skipSpace();
            expect(pos_ < text_.size(), "unterminated start tag");
            if (text_.compare(pos_, 2, "/>") == 0)
            {
                pos_ += 2;
                return e;
            }
            if (text_[pos_] == '>')
            {
                ++pos_;
                break;
            }
            const std::string key = name();
            expect(text_[pos_] == '=' && text_[pos_ + 1] == '"', "expected =\"");
            pos_ += 2;
            const std::size_t end = text_.find('"', pos_);
            expect(end != std::string::npos, "unterminated attribute");
            expect(!e.attributes.count(key), "duplicate attribute " + key);
            e.attributes[key] = text_.substr(pos_, end - pos_);
            expect(e.attributes[key].find('<') == std::string::npos, "'<' in attribute");
            pos_ = end + 1;
        }
        for (;;)
        {
            const std::size_t open = text_.find('<', pos_);
            expect(open != std::string::npos, "unclosed <" + e.name + ">");
            e.text += text_.substr(pos_, open - pos_);
            pos_ = open;
            if (text_.compare(pos_, 2, "</") == 0)
            {
                pos_ += 2;
                expect(name() == e.name, "end tag does not match <" + e.name + ">");
                skipSpace();
                expect(text_[pos_] == '>', "expected '>'");
                ++pos_;
                return e;
            }
            e.children.push_back(element());
        }
    }

    std::string text_;
    std::size_t pos_ = 0;
};

std::string contents(const fs::path& file)
{
    std::ifstream in(file, std::ios::binary);
    EXPECT_TRUE(in.good()) << file;
    std::stringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

XmlElement readXml(const fs::path& file)
{
    return XmlReader(contents(file)).document();
}

std::size_t count(const XmlElement& array)
{
    return array.values().size();
}

//- A binary .vtp: its XML (read with XmlReader) and the raw data appended after it.
struct BinaryVtp
{
    XmlElement root;
    std::string appended;

    explicit BinaryVtp(const std::string& file)
    {
        const std::string open = "  <AppendedData encoding=\"raw\">\n   _";
        const std::string close = "\n  </AppendedData>\n</VTKFile>\n";
        const std::size_t start = file.find(open);
        if
        (
            start == std::string::npos || file.size() < start + open.size() + close.size()
         || file.compare(file.size() - close.size(), close.size(), close) != 0
        )
        {
            throw std::runtime_error("no appended raw data");
        }
        root = XmlReader(file.substr(0, start) + "</VTKFile>\n").document();
        appended = file.substr(start + open.size(), file.size() - close.size() - start - open.size());
    }

    const XmlElement& piece() const { return root.child("PolyData").child("Piece"); }

    std::uint64_t word(std::size_t at) const
    {
        std::uint64_t w = 0;
        EXPECT_LE(at + sizeof w, appended.size());
        std::memcpy(&w, appended.data() + at, sizeof w);
        return w;
    }

    //- One array's bytes: VTK's compressed blocks undone with zlib's uncompress.
    std::string bytes(const XmlElement& array) const
    {
        EXPECT_EQ(array.attributes.at("format"), "appended");
        const std::size_t offset = std::stoul(array.attributes.at("offset"));
        const std::uint64_t blocks = word(offset);
        const std::uint64_t blockSize = word(offset + 8);
        const std::uint64_t lastSize = word(offset + 16);
        std::size_t at = offset + 24 + 8*blocks;
        std::string decoded;
        for (std::uint64_t k = 0; k < blocks; ++k)
        {
            const std::uint64_t compressed = word(offset + 24 + 8*k);
            const uLongf expected = (k + 1 == blocks && lastSize != 0) ? lastSize : blockSize;
            uLongf size = expected;
            std::string block(size, '\0');
            EXPECT_LE(at + compressed, appended.size());
            EXPECT_EQ
            (
                uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                           reinterpret_cast<const Bytef*>(appended.data() + at), compressed),
                Z_OK
            );
            EXPECT_EQ(size, expected);
            decoded += block;
            at += compressed;
        }
        return decoded;
    }
};

template<class T>
std::string bytesOf(const std::vector<T>& values)
{
    return std::string(reinterpret_cast<const char*>(values.data()), values.size()*sizeof(T));
}

//- The attributes of every DataArray but format and offset, in file order.
std::vector<std::map<std::string, std::string>> arrayHeads(const XmlElement& e)
{
    std::vector<std::map<std::string, std::string>> heads;
    for (const XmlElement& c : e.children)
    {
        if (c.name == "DataArray")
        {
            std::map<std::string, std::string> head = c.attributes;
            head.erase("format");
            head.erase("offset");
            heads.push_back(head);
        }
        for (auto& h : arrayHeads(c))
        {
            heads.push_back(h);
        }
    }
    return heads;
}

ParticleFrame threeParticles()
{
    ParticleFrame p;
    p.position = {Vec3(0, 0, 0), Vec3(0.1, 0.2, 0.3), Vec3(-1.5, 2.5e-3, 1e-12)};
    p.velocity = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    p.force = {Vec3(10, 0, 0), Vec3(0, -20, 0), Vec3(0, 0, 30.5)};
    p.radius = {0.05, 0.0625, 0.075};
    p.tag = {1, 2, 5000000000L};
    p.bondCount = {3, 0, 12};
    p.fixed = {0, 1, 0};
    return p;
}

BondFrame twoBonds()
{
    BondFrame b;
    b.points = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(1, 1, 1), Vec3(1, 1.1, 1)};
    b.ends = {{0, 1}, {2, 3}};
    b.family = {0, 1};
    b.state = {0, 1};
    b.mode = {0, 2};
    b.time = {-1.0, 0.375};
    return b;
}

class VtkFiles : public ::testing::Test
{
protected:
    void SetUp() override
    {
        const std::string name =
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path()
             / ("iceDEM_Vtk_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
    }

    void TearDown() override
    {
        fs::remove_all(dir_);
    }

    fs::path dir_;
};

} // namespace


TEST_F(VtkFiles, ParticlesArePolyDataVertices)
{
    const ParticleFrame frame = threeParticles();
    writeParticlesVtp((dir_/"VTK"/"particles_0.vtp").string(), frame, VtkFormat::ascii);
    const XmlElement root = readXml(dir_/"VTK"/"particles_0.vtp");

    EXPECT_EQ(root.name, "VTKFile");
    EXPECT_EQ(root.attributes.at("type"), "PolyData");
    const XmlElement& piece = root.child("PolyData").child("Piece");
    EXPECT_EQ(piece.attributes.at("NumberOfPoints"), "3");
    EXPECT_EQ(piece.attributes.at("NumberOfVerts"), "3");
    EXPECT_EQ(piece.attributes.at("NumberOfLines"), "0");

    const XmlElement& pointData = piece.child("PointData");
    EXPECT_EQ(count(pointData.array("radius")), 3u);
    EXPECT_EQ(count(pointData.array("velocity")), 9u);
    EXPECT_EQ(count(pointData.array("force")), 9u);
    EXPECT_EQ(count(pointData.array("tag")), 3u);
    EXPECT_EQ(count(pointData.array("bondCount")), 3u);
    EXPECT_EQ(count(pointData.array("fixed")), 3u);
    EXPECT_EQ(pointData.array("velocity").attributes.at("NumberOfComponents"), "3");
    EXPECT_EQ(pointData.array("tag").attributes.at("type"), "Int64");
    EXPECT_EQ(pointData.array("tag").values()[2], 5e9);
    EXPECT_EQ(pointData.array("radius").values()[1], 0.0625);
    EXPECT_EQ(pointData.array("force").values()[8], 30.5);

    const std::vector<double> points = piece.child("Points").child("DataArray").values();
    ASSERT_EQ(points.size(), 9u);
    EXPECT_EQ(points[6], -1.5);
    EXPECT_EQ(points[7], 2.5e-3);
    EXPECT_EQ(points[8], 1e-12);

    const XmlElement& verts = piece.child("Verts");
    EXPECT_EQ(verts.array("connectivity").values(), (std::vector<double>{0, 1, 2}));
    EXPECT_EQ(verts.array("offsets").values(), (std::vector<double>{1, 2, 3}));
}


TEST_F(VtkFiles, BondsArePolyDataLinesWithCellData)
{
    writeBondsVtp((dir_/"bonds_0.vtp").string(), twoBonds(), VtkFormat::ascii);
    const XmlElement root = readXml(dir_/"bonds_0.vtp");

    const XmlElement& piece = root.child("PolyData").child("Piece");
    EXPECT_EQ(piece.attributes.at("NumberOfPoints"), "4");
    EXPECT_EQ(piece.attributes.at("NumberOfVerts"), "0");
    EXPECT_EQ(piece.attributes.at("NumberOfLines"), "2");

    const XmlElement& cellData = piece.child("CellData");
    EXPECT_EQ(cellData.array("family").values(), (std::vector<double>{0, 1}));
    EXPECT_EQ(cellData.array("state").values(), (std::vector<double>{0, 1}));
    EXPECT_EQ(cellData.array("mode").values(), (std::vector<double>{0, 2}));
    EXPECT_EQ(cellData.array("breakTime").values(), (std::vector<double>{-1.0, 0.375}));

    const std::vector<double> points = piece.child("Points").child("DataArray").values();
    EXPECT_EQ(points, (std::vector<double>{0, 0, 0, 0.1, 0, 0, 1, 1, 1, 1, 1.1, 1}));
    const XmlElement& lines = piece.child("Lines");
    EXPECT_EQ(lines.array("connectivity").values(), (std::vector<double>{0, 1, 2, 3}));
    EXPECT_EQ(lines.array("offsets").values(), (std::vector<double>{2, 4}));
}


TEST_F(VtkFiles, EmptyFramesAreWellFormed)
{
    writeParticlesVtp((dir_/"p.vtp").string(), ParticleFrame(), VtkFormat::ascii);
    writeBondsVtp((dir_/"b.vtp").string(), BondFrame(), VtkFormat::ascii);
    for (const char* file : {"p.vtp", "b.vtp"})
    {
        const XmlElement piece = readXml(dir_/file).child("PolyData").child("Piece");
        EXPECT_EQ(piece.attributes.at("NumberOfPoints"), "0") << file;
        EXPECT_EQ(count(piece.child("Points").child("DataArray")), 0u) << file;
    }
}


TEST_F(VtkFiles, OptionalArraysLeftOutWrongLengthsRejected)
{
    ParticleFrame frame;
    frame.position = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
    frame.radius = {0.1, 0.1};
    const XmlElement pointData =
        XmlReader(particlesVtp(frame, VtkFormat::ascii)).document().child("PolyData").child("Piece")
       .child("PointData");
    EXPECT_EQ(pointData.children.size(), 1u);
    EXPECT_EQ(count(pointData.array("radius")), 2u);

    frame.tag = {1};
    EXPECT_THROW(particlesVtp(frame, VtkFormat::ascii), std::invalid_argument);

    BondFrame bonds = twoBonds();
    bonds.ends[1][1] = 4;
    EXPECT_THROW(bondsVtp(bonds, VtkFormat::binary), std::invalid_argument);
    bonds.ends[1][1] = -1;
    EXPECT_THROW(bondsVtp(bonds, VtkFormat::ascii), std::invalid_argument);
    bonds = twoBonds();
    bonds.time = {1.0};
    EXPECT_THROW(bondsVtp(bonds, VtkFormat::binary), std::invalid_argument);
}


TEST(VtkAscii, ByteIdenticalToTheFilesBeforeBinary)
{
    const fs::path before = fs::path(ICEDEM_SOURCE_DIR)/"tests"/"unit"/"data"/"vtkAscii";
    EXPECT_EQ(particlesVtp(threeParticles(), VtkFormat::ascii), contents(before/"particles.vtp"));
    EXPECT_EQ(bondsVtp(twoBonds(), VtkFormat::ascii), contents(before/"bonds.vtp"));
    EXPECT_EQ(particlesVtp(ParticleFrame(), VtkFormat::ascii), contents(before/"emptyParticles.vtp"));
    EXPECT_EQ(bondsVtp(BondFrame(), VtkFormat::ascii), contents(before/"emptyBonds.vtp"));
}


TEST_F(VtkFiles, BinaryParticlesDecodeToTheirArrays)
{
    ParticleFrame frame = threeParticles();
    frame.block = {-1, 4, 4};
    writeParticlesVtp((dir_/"p.vtp").string(), frame, VtkFormat::binary);
    const BinaryVtp file(contents(dir_/"p.vtp"));

    EXPECT_EQ(file.root.attributes.at("compressor"), "vtkZLibDataCompressor");
    EXPECT_EQ(file.root.attributes.at("header_type"), "UInt64");
    EXPECT_EQ(file.root.attributes.at("byte_order"), "LittleEndian");
    // The same piece, arrays, types and components as ascii.
    const XmlElement ascii = XmlReader(particlesVtp(frame, VtkFormat::ascii)).document();
    EXPECT_EQ(file.piece().attributes, ascii.child("PolyData").child("Piece").attributes);
    EXPECT_EQ(arrayHeads(file.root), arrayHeads(ascii));
    EXPECT_EQ(file.piece().child("PointData").attributes,
              ascii.child("PolyData").child("Piece").child("PointData").attributes);

    const XmlElement& pointData = file.piece().child("PointData");
    EXPECT_EQ(file.bytes(pointData.array("radius")), bytesOf(frame.radius));
    EXPECT_EQ(file.bytes(pointData.array("velocity")), bytesOf(frame.velocity));
    EXPECT_EQ(file.bytes(pointData.array("force")), bytesOf(frame.force));
    EXPECT_EQ(file.bytes(pointData.array("tag")), bytesOf(frame.tag));
    EXPECT_EQ(file.bytes(pointData.array("bondCount")), bytesOf(frame.bondCount));
    EXPECT_EQ(file.bytes(pointData.array("fixed")), bytesOf(frame.fixed));
    EXPECT_EQ(file.bytes(pointData.array("block")), bytesOf(frame.block));
    EXPECT_EQ(file.bytes(file.piece().child("Points").child("DataArray")), bytesOf(frame.position));
    const XmlElement& verts = file.piece().child("Verts");
    EXPECT_EQ(file.bytes(verts.array("connectivity")), bytesOf(std::vector<long>{0, 1, 2}));
    EXPECT_EQ(file.bytes(verts.array("offsets")), bytesOf(std::vector<long>{1, 2, 3}));
}


TEST_F(VtkFiles, BinaryBondsWriteSharedPointsOnce)
{
    BondFrame frame;
    frame.points = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.05, 0.08, 0), Vec3(2, 2, 2), Vec3(2.1, 2, 2)};
    frame.ends = {{0, 1}, {1, 2}, {2, 0}, {3, 4}};
    frame.family = {0, 0, 1, 0};
    frame.state = {0, 0, 0, 1};
    frame.mode = {0, 0, 0, 2};
    frame.time = {-1, -1, -1, 0.25};
    writeBondsVtp((dir_/"b.vtp").string(), frame, VtkFormat::binary);
    const BinaryVtp file(contents(dir_/"b.vtp"));

    EXPECT_EQ(file.piece().attributes.at("NumberOfPoints"), "5");
    EXPECT_EQ(file.piece().attributes.at("NumberOfLines"), "4");
    const XmlElement ascii = XmlReader(bondsVtp(frame, VtkFormat::ascii)).document();
    EXPECT_EQ(ascii.child("PolyData").child("Piece").attributes.at("NumberOfPoints"), "8");
    EXPECT_EQ(arrayHeads(file.root), arrayHeads(ascii));

    const XmlElement& cellData = file.piece().child("CellData");
    EXPECT_EQ(file.bytes(cellData.array("family")), bytesOf(frame.family));
    EXPECT_EQ(file.bytes(cellData.array("state")), bytesOf(frame.state));
    EXPECT_EQ(file.bytes(cellData.array("mode")), bytesOf(frame.mode));
    EXPECT_EQ(file.bytes(cellData.array("breakTime")), bytesOf(frame.time));
    EXPECT_EQ(file.bytes(file.piece().child("Points").child("DataArray")), bytesOf(frame.points));
    const XmlElement& lines = file.piece().child("Lines");
    EXPECT_EQ(file.bytes(lines.array("connectivity")), bytesOf(std::vector<long>{0, 1, 1, 2, 2, 0, 3, 4}));
    EXPECT_EQ(file.bytes(lines.array("offsets")), bytesOf(std::vector<long>{2, 4, 6, 8}));
}


TEST_F(VtkFiles, BinaryArraysSpanBlocksAndEmptyFramesAreWellFormed)
{
    // 5000 points: 120,000 bytes, three full blocks of 32,768 and one of 21,696;
    // 4096 radii: 32,768 bytes, one full block (last size 0).
    ParticleFrame frame;
    for (int i = 0; i < 5000; ++i)
    {
        frame.position.push_back(Vec3(std::sin(i), std::cos(0.3*i), 1e-3*i));
    }
    const std::string points = particlesVtp(frame, VtkFormat::binary);
    const BinaryVtp file(points);
    const XmlElement& pointsArray = file.piece().child("Points").child("DataArray");
    const std::size_t offset = std::stoul(pointsArray.attributes.at("offset"));
    EXPECT_EQ(file.word(offset), 4u);
    EXPECT_EQ(file.word(offset + 8), 32768u);
    EXPECT_EQ(file.word(offset + 16), 120000u - 3*32768u);
    EXPECT_EQ(file.bytes(pointsArray), bytesOf(frame.position));

    ParticleFrame exact;
    exact.position.assign(4096, Vec3(0.5, 0.25, 0.125));
    exact.radius.assign(4096, 0.01);
    const BinaryVtp exactFile(particlesVtp(exact, VtkFormat::binary));
    const XmlElement& radius = exactFile.piece().child("PointData").array("radius");
    const std::size_t at = std::stoul(radius.attributes.at("offset"));
    EXPECT_EQ(exactFile.word(at), 1u);
    EXPECT_EQ(exactFile.word(at + 16), 0u);
    EXPECT_EQ(exactFile.bytes(radius), bytesOf(exact.radius));

    for (const std::string& empty :
         {particlesVtp(ParticleFrame(), VtkFormat::binary), bondsVtp(BondFrame(), VtkFormat::binary)})
    {
        const BinaryVtp emptyFile(empty);
        EXPECT_EQ(emptyFile.piece().attributes.at("NumberOfPoints"), "0");
        EXPECT_EQ(emptyFile.bytes(emptyFile.piece().child("Points").child("DataArray")), "");
    }
}


TEST(VtkFormatEntry, BinaryByDefaultAsciiByNameUnknownRefused)
{
    EXPECT_EQ(readVtkFormat(Dictionary::parse("writeInterval 0.01;", "system/controlDict")),
              VtkFormat::binary);
    EXPECT_EQ(readVtkFormat(Dictionary::parse("vtkFormat ascii;", "system/controlDict")),
              VtkFormat::ascii);
    EXPECT_EQ(readVtkFormat(Dictionary::parse("vtkFormat binary;", "system/controlDict")),
              VtkFormat::binary);
    try
    {
        readVtkFormat(Dictionary::parse("\nvtkFormat legacy;\n", "system/controlDict"));
        FAIL() << "vtkFormat legacy accepted";
    }
    catch (const InputError& e)
    {
        EXPECT_EQ(e.file(), "system/controlDict");
        EXPECT_EQ(e.entry(), "vtkFormat");
        const std::string what = e.what();
        EXPECT_NE(what.find("line 2"), std::string::npos) << what;
        EXPECT_NE(what.find("unknown value 'legacy'; allowed: ascii binary"), std::string::npos) << what;
    }
}


TEST_F(VtkFiles, PvdListsEntriesInTimeOrderAfterEveryAdd)
{
    const fs::path pvd = dir_/"particles.pvd";
    PvdCollection series(pvd.string());
    const std::vector<std::pair<double, std::string>> adds =
        {{0.5, "VTK/p_2.vtp"}, {0.0, "VTK/p_0.vtp"}, {0.25, "VTK/p_1.vtp"},
         {1.0, "VTK/a&b.vtp"}};
    for (std::size_t k = 0; k < adds.size(); ++k)
    {
        series.add(adds[k].first, adds[k].second);

        const XmlElement root = readXml(pvd);
        EXPECT_EQ(root.attributes.at("type"), "Collection");
        const XmlElement& collection = root.child("Collection");
        ASSERT_EQ(collection.children.size(), k + 1);
        for (std::size_t i = 1; i < collection.children.size(); ++i)
        {
            EXPECT_LT(std::stod(collection.children[i - 1].attributes.at("timestep")),
                      std::stod(collection.children[i].attributes.at("timestep")));
        }
        for (const XmlElement& dataSet : collection.children)
        {
            EXPECT_EQ(dataSet.name, "DataSet");
            EXPECT_EQ(dataSet.attributes.at("part"), "0");
            EXPECT_TRUE(dataSet.attributes.count("file"));
        }
    }
    EXPECT_EQ(readXml(pvd).child("Collection").children[3].attributes.at("file"),
              "VTK/a&amp;b.vtp");

    const PvdCollection reread = PvdCollection::read(pvd.string());
    ASSERT_EQ(reread.entries().size(), 4u);
    EXPECT_EQ(reread.entries()[1].time, 0.25);
    EXPECT_EQ(reread.entries()[1].file, "VTK/p_1.vtp");
    EXPECT_EQ(reread.entries()[3].file, "VTK/a&b.vtp");
}


TEST_F(VtkFiles, PvdReplacesSameTimeStoresRelativeAndDropsLaterOnRestart)
{
    const fs::path pvd = dir_/"bonds.pvd";
    PvdCollection series(pvd.string());
    series.add(0.0, "VTK/b_0.vtp");
    series.add(0.1, "VTK/b_1.vtp");
    series.add(0.1, (fs::absolute(dir_)/"VTK"/"b_1_again.vtp").string());
    ASSERT_EQ(series.entries().size(), 2u);
    EXPECT_EQ(series.entries()[1].file, "VTK/b_1_again.vtp");

    series.add(0.2, "VTK/b_2.vtp");
    PvdCollection restarted = PvdCollection::read(pvd.string());
    restarted.removeAfter(0.1);
    restarted.add(0.15, "VTK/b_r.vtp");
    const PvdCollection onDisk = PvdCollection::read(pvd.string());
    ASSERT_EQ(onDisk.entries().size(), 3u);
    EXPECT_EQ(onDisk.entries()[2].time, 0.15);

    EXPECT_THROW(PvdCollection::read((dir_/"missing.pvd").string()), std::runtime_error);
}


TEST(VtkXmlReader, DetectsMalformedXml)
{
    EXPECT_THROW(XmlReader("<a><b></a></b>").document(), std::runtime_error);
    EXPECT_THROW(XmlReader("<a x=\"1></a>").document(), std::runtime_error);
    EXPECT_THROW(XmlReader("<a></a><b/>").document(), std::runtime_error);
    EXPECT_NO_THROW(XmlReader("<?xml version=\"1.0\"?>\n<a x=\"1\"><b/>t</a>\n").document());
}
