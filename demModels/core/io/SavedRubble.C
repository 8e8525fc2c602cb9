#include "SavedRubble.H"

#include "AtomicFile.H"
#include "Hdf5Io.H"
#include "InputError.H"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>

namespace iceDEM
{

namespace
{

//- One column of a table: a name and how to get or set it from a row.
template<class Row>
struct Column
{
    const char* name;
    std::function<double(const Row&)> get;
    std::function<void(Row&, double)> set;
};

template<class Row>
std::vector<Column<Row>> vectorColumns(const char* x, const char* y, const char* z, Vec3 Row::*member)
{
    std::vector<Column<Row>> c;
    const char* names[3] = {x, y, z};
    for (int k = 0; k < 3; ++k)
    {
        c.push_back({names[k], [=](const Row& r) { return (r.*member)[k]; },
                               [=](Row& r, double v) { (r.*member)[k] = v; }});
    }
    return c;
}

std::vector<Column<SavedParticle>> particleColumns()
{
    using P = SavedParticle;
    std::vector<Column<P>> c;
    for (auto v : {vectorColumns<P>("x", "y", "z", &P::position),
                   vectorColumns<P>("vx", "vy", "vz", &P::velocity),
                   vectorColumns<P>("wx", "wy", "wz", &P::angularVelocity)})
    {
        c.insert(c.end(), v.begin(), v.end());
    }
    c.push_back({"radius", [](const P& p) { return p.radius; }, [](P& p, double v) { p.radius = v; }});
    c.push_back({"density", [](const P& p) { return p.density; }, [](P& p, double v) { p.density = v; }});
    c.push_back({"block", [](const P& p) { return double(p.block); }, [](P& p, double v) { p.block = int(v); }});
    c.push_back({"type", [](const P& p) { return double(p.type); }, [](P& p, double v) { p.type = int(v); }});
    return c;
}

std::vector<Column<BondState>> bondColumns()
{
    using B = BondState;
    std::vector<Column<B>> c
    {
        {"tagA", [](const B& b) { return double(b.tagA); }, [](B& b, double v) { b.tagA = long(v); }},
        {"tagB", [](const B& b) { return double(b.tagB); }, [](B& b, double v) { b.tagB = long(v); }},
        {"family", [](const B& b) { return double(static_cast<int>(b.family)); },
                   [](B& b, double v) { b.family = static_cast<BondFamily>(int(v)); }},
        {"restLength", [](const B& b) { return b.restLength; }, [](B& b, double v) { b.restLength = v; }},
        {"twistAngle", [](const B& b) { return b.twistAngle; }, [](B& b, double v) { b.twistAngle = v; }},
        {"tensileStrength", [](const B& b) { return b.tensileStrength; }, [](B& b, double v) { b.tensileStrength = v; }},
        {"shearStrength", [](const B& b) { return b.shearStrength; }, [](B& b, double v) { b.shearStrength = v; }},
    };
    for (auto v : {vectorColumns<B>("shearX", "shearY", "shearZ", &B::shearDisplacement),
                   vectorColumns<B>("bendingX", "bendingY", "bendingZ", &B::bendingAngle)})
    {
        c.insert(c.end(), v.begin(), v.end());
    }
    return c;
}

template<class Row>
void writeTable(hid_t file, const char* group, const std::vector<Row>& rows,
                const std::vector<Column<Row>>& columns, const std::string& path)
{
    H5Id g(H5Gcreate2(file, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           hdf5Failure(path, std::string("cannot create group ") + group));
    std::vector<double> values(rows.size());
    for (const Column<Row>& c : columns)
    {
        for (std::size_t k = 0; k < rows.size(); ++k)
        {
            values[k] = c.get(rows[k]);
        }
        writeDataset(g.get(), c.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values.data(), rows.size(), path);
    }
}

template<class Row>
std::vector<Row> readTable(hid_t file, const char* group, const std::vector<Column<Row>>& columns,
                           const std::string& path)
{
    H5Id g(H5Gopen2(file, group, H5P_DEFAULT), H5Gclose, hdf5Failure(path, std::string("no group ") + group));
    std::vector<Row> rows;
    for (const Column<Row>& c : columns)
    {
        const std::vector<double> values = readDataset<double>(g.get(), c.name, H5T_NATIVE_DOUBLE, path);
        if (rows.empty())
        {
            rows.resize(values.size());
        }
        if (values.size() != rows.size())
        {
            throw std::runtime_error(hdf5Failure(path, std::string(group) + "/" + c.name + " has the wrong length"));
        }
        for (std::size_t k = 0; k < rows.size(); ++k)
        {
            c.set(rows[k], values[k]);
        }
    }
    return rows;
}

void writeScalarAttribute(hid_t object, const char* name, double value, const std::string& path)
{
    const std::string context = hdf5Failure(path, std::string("cannot write attribute ") + name);
    H5Id space(H5Screate(H5S_SCALAR), H5Sclose, context);
    H5Id attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, context);
    if (H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    {
        throw std::runtime_error(context);
    }
}

double readScalarAttribute(hid_t object, const char* name, const std::string& path)
{
    const std::string context = hdf5Failure(path, std::string("no attribute ") + name);
    H5Id attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, context);
    double value = 0.0;
    if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    {
        throw std::runtime_error(context);
    }
    return value;
}


//- The saved stage in the open HDF5 file (std::runtime_error where a part is missing).
SavedRubble readStage(hid_t file, const std::string& path)
{
    SavedRubble r;
    r.particles = readTable(file, "particles", particleColumns(), path);
    r.bonds = readTable(file, "bonds", bondColumns(), path);
    H5Id root(H5Gopen2(file, "/", H5P_DEFAULT), H5Gclose, hdf5Failure(path, "no root group"));
    r.time = readScalarAttribute(root.get(), "time", path);
    r.waterLevel = readScalarAttribute(root.get(), "waterLevel", path);
    r.provenance = readStringAttributeOrEmpty(root.get(), "provenance", path);
    r.kind = readStringAttributeOrEmpty(root.get(), "kind", path);
    r.restart = readStringAttributeOrEmpty(root.get(), "restart", path);
    if (H5Aexists(root.get(), "plateBottom") > 0 && H5Aexists(root.get(), "plateTop") > 0)
    {
        r.plateBottom = readScalarAttribute(root.get(), "plateBottom", path);
        r.plateTop = readScalarAttribute(root.get(), "plateTop", path);
        if (H5Aexists(root.get(), "plateHoldPressure") > 0)
        {
            r.plateHoldPressure = readScalarAttribute(root.get(), "plateHoldPressure", path);
        }
    }
    if (H5Aexists(root.get(), "contactYoungsModulus") > 0)
    {
        r.contactYoungsModulus = readScalarAttribute(root.get(), "contactYoungsModulus", path);
    }
    if (H5Aexists(root.get(), "wallSeconds") > 0)
    {
        r.wallSeconds = readScalarAttribute(root.get(), "wallSeconds", path);
    }
    return r;
}

} // namespace


void SavedRubble::write(const std::string& path) const
{
    QuietHdf5Errors quiet;
    writeAtomically(path, [&](const std::string& tempPath)
    {
        H5Id file(H5Fcreate(tempPath.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                  hdf5Failure(path, "cannot create file"));
        writeTable(file.get(), "particles", particles, particleColumns(), path);
        writeTable(file.get(), "bonds", bonds, bondColumns(), path);
        H5Id root(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose, hdf5Failure(path, "no root group"));
        writeScalarAttribute(root.get(), "time", time, path);
        writeScalarAttribute(root.get(), "waterLevel", waterLevel, path);
        writeStringAttribute(root.get(), "description", description.empty() ? " " : description, path);
        if (!provenance.empty())
        {
            writeStringAttribute(root.get(), "provenance", provenance, path);
        }
        if (!kind.empty())
        {
            writeStringAttribute(root.get(), "kind", kind, path);
        }
        if (!restart.empty())
        {
            writeStringAttribute(root.get(), "restart", restart, path);
        }
        if (std::isfinite(plateBottom) && std::isfinite(plateTop))
        {
            writeScalarAttribute(root.get(), "plateBottom", plateBottom, path);
            writeScalarAttribute(root.get(), "plateTop", plateTop, path);
            writeScalarAttribute(root.get(), "plateHoldPressure", plateHoldPressure, path);
        }
        if (std::isfinite(contactYoungsModulus))
        {
            writeScalarAttribute(root.get(), "contactYoungsModulus", contactYoungsModulus, path);
        }
        if (wallSeconds > 0.0)
        {
            writeScalarAttribute(root.get(), "wallSeconds", wallSeconds, path);
        }
    });
}


SavedRubble SavedRubble::read(const std::string& path, const std::string& expectedKind)
{
    if (!std::filesystem::exists(path))
    {
        throw InputError(path, "(file)", "does not exist");
    }
    if (H5Fis_hdf5(path.c_str()) <= 0)
    {
        throw InputError(path, "(file)", "is not an HDF5 file, or is truncated: not a saved stage of this program");
    }
    QuietHdf5Errors quiet;
    const hid_t opened = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (opened < 0)
    {
        // The signature is there but the file ends before what its superblock promises.
        throw InputError(path, "(file)", "is truncated or damaged: it begins as an HDF5 file ("
            + std::to_string(std::filesystem::file_size(path)) + " bytes) but HDF5 cannot open it;"
            " stages are written whole (a temporary file, then renamed), so a copy or a full disk"
            " cut this one short: copy it again or rebuild the stage");
    }
    H5Id file(opened, H5Fclose, hdf5Failure(path, "cannot open file (saved rubble)"));
    SavedRubble r;
    try
    {
        r = readStage(file.get(), path);
    }
    catch (const std::runtime_error& e)
    {
        throw InputError(path, "(file)", std::string("is not a readable saved stage (particles, bonds, time): ")
            + e.what());
    }
    if (!expectedKind.empty() && r.kind != expectedKind)
    {
        throw InputError(path, "kind", "holds " + (r.kind.empty() ? std::string("no kind (written by an older version)")
            : "a " + r.kind) + ", where a " + expectedKind + " is needed");
    }
    return r;
}


bool operator==(const SavedParticle& a, const SavedParticle& b)
{
    return a.position == b.position && a.velocity == b.velocity && a.angularVelocity == b.angularVelocity
        && a.radius == b.radius && a.density == b.density && a.block == b.block && a.type == b.type;
}


bool operator==(const BondState& a, const BondState& b)
{
    return a.tagA == b.tagA && a.tagB == b.tagB && a.family == b.family && a.restLength == b.restLength
        && a.shearDisplacement == b.shearDisplacement && a.twistAngle == b.twistAngle
        && a.bendingAngle == b.bendingAngle && a.tensileStrength == b.tensileStrength
        && a.shearStrength == b.shearStrength;
}

} // namespace iceDEM
