#include "Checkpoint.H"

#include "AtomicFile.H"

#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace iceDEM
{

namespace
{

constexpr std::uint64_t magic = 0x69636544454d3035ULL;   // "iceDEM05"
constexpr std::uint64_t magicOfVersion1 = 0x69636544454d3031ULL;   // LoadingState without liggghtsStepAtStart
constexpr std::uint64_t magicOfVersion2 = 0x69636544454d3032ULL;   // without the inputs' provenance
constexpr std::uint64_t magicOfVersion3 = 0x69636544454d3033ULL;   // break events without their separation
constexpr std::uint64_t magicOfVersion4 = 0x69636544454d3034ULL;   // LoadingState without the wall time

class Writer
{
public:
    explicit Writer(std::ostream& out) : out_(out) {}

    template<class T>
    void put(const T& value)
    {
        out_.write(reinterpret_cast<const char*>(&value), sizeof(T));
    }

    void put(const Vec3& v)
    {
        put(v.x());
        put(v.y());
        put(v.z());
    }

    void put(const std::string& s)
    {
        put(static_cast<std::uint64_t>(s.size()));
        out_.write(s.data(), static_cast<std::streamsize>(s.size()));
    }

private:
    std::ostream& out_;
};

class Reader
{
public:
    Reader(std::istream& in, const std::string& path) : in_(in), path_(path) {}

    template<class T>
    T get()
    {
        T value;
        in_.read(reinterpret_cast<char*>(&value), sizeof(T));
        if (!in_)
        {
            throw std::runtime_error(path_ + ": checkpoint is truncated");
        }
        return value;
    }

    Vec3 getVec3()
    {
        const double x = get<double>(), y = get<double>(), z = get<double>();
        return Vec3(x, y, z);
    }

    std::string getString()
    {
        std::string s(getCount(1ULL << 28), '\0');
        in_.read(s.data(), static_cast<std::streamsize>(s.size()));
        return s;
    }

    std::uint64_t getCount(std::uint64_t limit)
    {
        const auto n = get<std::uint64_t>();
        if (n > limit)
        {
            throw std::runtime_error(path_ + ": checkpoint is corrupt (count " + std::to_string(n) + ")");
        }
        return n;
    }

private:
    std::istream& in_;
    const std::string& path_;
};

} // namespace


void appendBondState(std::vector<double>& out, const BondState& b)
{
    out.insert
    (
        out.end(),
        {
            double(b.tagA), double(b.tagB), double(static_cast<int>(b.family)), b.restLength,
            b.shearDisplacement.x(), b.shearDisplacement.y(), b.shearDisplacement.z(), b.twistAngle,
            b.bendingAngle.x(), b.bendingAngle.y(), b.bendingAngle.z(), b.tensileStrength, b.shearStrength
        }
    );
}


BondState bondStateFrom(const double* v)
{
    BondState b;
    b.tagA = static_cast<long>(v[0]);
    b.tagB = static_cast<long>(v[1]);
    b.family = static_cast<BondFamily>(static_cast<int>(v[2]));
    b.restLength = v[3];
    b.shearDisplacement = Vec3(v[4], v[5], v[6]);
    b.twistAngle = v[7];
    b.bendingAngle = Vec3(v[8], v[9], v[10]);
    b.tensileStrength = v[11];
    b.shearStrength = v[12];
    return b;
}


void Checkpoint::write(const std::string& path) const
{
    writeStreamAtomically(path, [&](std::ostream& out)
    {
        Writer w(out);
        w.put(magic);
        w.put(state);
        w.put(provenance);
        w.put(static_cast<std::uint64_t>(curveColumns.size()));
        for (const std::string& c : curveColumns) w.put(c);
        w.put(static_cast<std::uint64_t>(curveRows.size()));
        for (const auto& row : curveRows)
        {
            w.put(static_cast<std::uint64_t>(row.size()));
            for (double v : row) w.put(v);
        }
        w.put(static_cast<std::uint64_t>(breaks.size()));
        for (const BreakEvent& e : breaks)
        {
            w.put(e.time);
            w.put(e.position);
            w.put(e.separation);
            w.put(static_cast<std::int64_t>(e.tagA));
            w.put(static_cast<std::int64_t>(e.tagB));
            w.put(static_cast<std::int32_t>(e.family));
            w.put(static_cast<std::int32_t>(e.mode));
        }
        w.put(static_cast<std::uint64_t>(bonds.size()));
        std::vector<double> flat;
        for (const BondState& b : bonds)
        {
            flat.clear();
            appendBondState(flat, b);
            for (double v : flat) w.put(v);
        }
        w.put(magic);
    });
}


Checkpoint Checkpoint::read(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
    {
        throw std::runtime_error(path + ": no checkpoint to resume from");
    }
    Reader r(in, path);
    const auto start = r.get<std::uint64_t>();
    if (start == magicOfVersion1 || start == magicOfVersion2 || start == magicOfVersion3
        || start == magicOfVersion4)
    {
        throw std::runtime_error(path + ": written by an older version of the program; delete the "
            "checkpoint folder and start again");
    }
    if (start != magic)
    {
        throw std::runtime_error(path + ": not an iceDEM checkpoint");
    }
    constexpr std::uint64_t limit = 1ULL << 32;
    Checkpoint c;
    c.state = r.get<LoadingState>();
    c.provenance = r.getString();
    for (auto n = r.getCount(1000); n > 0; --n) c.curveColumns.push_back(r.getString());
    for (auto n = r.getCount(limit); n > 0; --n)
    {
        std::vector<double> row(r.getCount(1000));
        for (double& v : row) v = r.get<double>();
        c.curveRows.push_back(std::move(row));
    }
    for (auto n = r.getCount(limit); n > 0; --n)
    {
        BreakEvent e;
        e.time = r.get<double>();
        e.position = r.getVec3();
        e.separation = r.getVec3();
        e.tagA = r.get<std::int64_t>();
        e.tagB = r.get<std::int64_t>();
        e.family = static_cast<BondFamily>(r.get<std::int32_t>());
        e.mode = static_cast<BreakMode>(r.get<std::int32_t>());
        c.breaks.push_back(e);
    }
    for (auto n = r.getCount(limit); n > 0; --n)
    {
        double values[bondStateDoubles];
        for (double& v : values) v = r.get<double>();
        c.bonds.push_back(bondStateFrom(values));
    }
    if (r.get<std::uint64_t>() != magic)
    {
        throw std::runtime_error(path + ": checkpoint is corrupt (no end marker)");
    }
    return c;
}

} // namespace iceDEM
