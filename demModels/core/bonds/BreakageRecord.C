#include "BreakageRecord.H"

#include "AtomicFile.H"
#include "Hdf5Io.H"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <tuple>

namespace iceDEM
{

namespace
{

constexpr const char* groupName = "breakage";
constexpr const char* familyCodes = "0=ice,1=freeze";
constexpr const char* modeCodes = "1=tension,2=shear,3=twist,4=bending";
constexpr const char* units = "time:s,x:m,y:m,z:m,dx:m,dy:m,dz:m";

bool validFamily(int code)
{
    return code >= 0 && code < nBondFamilies;
}

bool validBreakMode(int code)
{
    return code >= static_cast<int>(BreakMode::tension)
        && code <= static_cast<int>(BreakMode::bending);
}


std::string failure(const std::string& path, const std::string& what)
{
    return "HDF5 breakage file '" + path + "': " + what;
}


void writeCountAttribute(hid_t object, std::int64_t count, const std::string& path)
{
    const std::string context = failure(path, "cannot write attribute count");
    H5Id space(H5Screate(H5S_SCALAR), H5Sclose, context);
    H5Id attribute
    (
        H5Acreate2(object, "count", H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose,
        context
    );
    if (H5Awrite(attribute.get(), H5T_NATIVE_INT64, &count) < 0)
    {
        throw std::runtime_error(context);
    }
}


void writeEvents
(
    const std::vector<BreakEvent>& events,
    const std::string& tempPath,
    const std::string& path
)
{
    const std::size_t n = events.size();
    std::vector<double> time(n), x(n), y(n), z(n), dx(n), dy(n), dz(n);
    std::vector<std::int64_t> tagA(n), tagB(n);
    std::vector<std::int32_t> family(n), mode(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        const BreakEvent& e = events[i];
        time[i] = e.time;
        x[i] = e.position.x();
        y[i] = e.position.y();
        z[i] = e.position.z();
        dx[i] = e.separation.x();
        dy[i] = e.separation.y();
        dz[i] = e.separation.z();
        tagA[i] = e.tagA;
        tagB[i] = e.tagB;
        family[i] = static_cast<std::int32_t>(e.family);
        mode[i] = static_cast<std::int32_t>(e.mode);
    }

    H5Id file(H5Fcreate(tempPath.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
              H5Fclose, failure(path, "cannot create file"));
    H5Id group(H5Gcreate2(file.get(), groupName, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               H5Gclose, failure(path, "cannot create group /breakage"));
    const hid_t g = group.get();
    writeDataset(g, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, time.data(), n, path);
    writeDataset(g, "x", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, x.data(), n, path);
    writeDataset(g, "y", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, y.data(), n, path);
    writeDataset(g, "z", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, z.data(), n, path);
    writeDataset(g, "dx", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dx.data(), n, path);
    writeDataset(g, "dy", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dy.data(), n, path);
    writeDataset(g, "dz", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dz.data(), n, path);
    writeDataset(g, "tagA", H5T_STD_I64LE, H5T_NATIVE_INT64, tagA.data(), n, path);
    writeDataset(g, "tagB", H5T_STD_I64LE, H5T_NATIVE_INT64, tagB.data(), n, path);
    writeDataset(g, "family", H5T_STD_I32LE, H5T_NATIVE_INT32, family.data(), n, path);
    writeDataset(g, "mode", H5T_STD_I32LE, H5T_NATIVE_INT32, mode.data(), n, path);
    writeStringAttribute(g, "familyCodes", familyCodes, path);
    writeStringAttribute(g, "modeCodes", modeCodes, path);
    writeStringAttribute(g, "units", units, path);
    writeCountAttribute(g, static_cast<std::int64_t>(n), path);
}

} // namespace


bool operator==(const BreakEvent& a, const BreakEvent& b)
{
    return a.time == b.time && a.position == b.position && a.separation == b.separation
        && a.tagA == b.tagA
        && a.tagB == b.tagB && a.family == b.family && a.mode == b.mode;
}


bool operator!=(const BreakEvent& a, const BreakEvent& b)
{
    return !(a == b);
}


bool eventOrder(const BreakEvent& a, const BreakEvent& b)
{
    const auto key = [](const BreakEvent& e)
    {
        return std::make_tuple(e.time, e.tagA, e.tagB, static_cast<int>(e.family),
                               static_cast<int>(e.mode));
    };
    return key(a) < key(b);
}


void BreakageRecord::append(const BreakEvent& event)
{
    if (!validFamily(static_cast<int>(event.family)))
    {
        throw std::invalid_argument("BreakageRecord: unknown bond family code "
                                    + std::to_string(static_cast<int>(event.family)));
    }
    if (!validBreakMode(static_cast<int>(event.mode)))
    {
        throw std::invalid_argument("BreakageRecord: a break event needs a break mode "
                                    "(tension, shear, twist or bending), got code "
                                    + std::to_string(static_cast<int>(event.mode)));
    }
    events_.push_back(event);
}


void BreakageRecord::append(const BreakageRecord& other)
{
    events_.insert(events_.end(), other.events_.begin(), other.events_.end());
}


std::size_t BreakageRecord::count(BreakMode mode) const
{
    return std::count_if(events_.begin(), events_.end(),
                         [mode](const BreakEvent& e) { return e.mode == mode; });
}


std::size_t BreakageRecord::count(BondFamily family) const
{
    return std::count_if(events_.begin(), events_.end(),
                         [family](const BreakEvent& e) { return e.family == family; });
}


std::size_t BreakageRecord::count(BondFamily family, BreakMode mode) const
{
    return std::count_if
    (
        events_.begin(), events_.end(),
        [family, mode](const BreakEvent& e) { return e.family == family && e.mode == mode; }
    );
}


void BreakageRecord::sort()
{
    std::sort(events_.begin(), events_.end(), eventOrder);
}


void BreakageRecord::writeHdf5(const std::string& path) const
{
    std::vector<BreakEvent> sorted(events_);
    std::sort(sorted.begin(), sorted.end(), eventOrder);
    QuietHdf5Errors quiet;
    writeAtomically
    (
        path,
        [&](const std::string& tempPath) { writeEvents(sorted, tempPath, path); }
    );
}


BreakageRecord BreakageRecord::readHdf5(const std::string& path)
{
    QuietHdf5Errors quiet;
    H5Id file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
              failure(path, "cannot open file"));
    H5Id group(H5Gopen2(file.get(), groupName, H5P_DEFAULT), H5Gclose,
               failure(path, "no group /breakage"));
    const hid_t g = group.get();
    const auto time = readDataset<double>(g, "time", H5T_NATIVE_DOUBLE, path);
    const auto x = readDataset<double>(g, "x", H5T_NATIVE_DOUBLE, path);
    const auto y = readDataset<double>(g, "y", H5T_NATIVE_DOUBLE, path);
    const auto z = readDataset<double>(g, "z", H5T_NATIVE_DOUBLE, path);
    const auto dx = readDataset<double>(g, "dx", H5T_NATIVE_DOUBLE, path);
    const auto dy = readDataset<double>(g, "dy", H5T_NATIVE_DOUBLE, path);
    const auto dz = readDataset<double>(g, "dz", H5T_NATIVE_DOUBLE, path);
    const auto tagA = readDataset<std::int64_t>(g, "tagA", H5T_NATIVE_INT64, path);
    const auto tagB = readDataset<std::int64_t>(g, "tagB", H5T_NATIVE_INT64, path);
    const auto family = readDataset<std::int32_t>(g, "family", H5T_NATIVE_INT32, path);
    const auto mode = readDataset<std::int32_t>(g, "mode", H5T_NATIVE_INT32, path);

    const std::size_t n = time.size();
    for (std::size_t size : {x.size(), y.size(), z.size(), dx.size(), dy.size(), dz.size(), tagA.size(), tagB.size(),
                             family.size(), mode.size()})
    {
        if (size != n)
        {
            throw std::runtime_error(failure(path, "datasets of different lengths"));
        }
    }

    BreakageRecord record;
    record.events_.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        if (!validFamily(family[i]) || !validBreakMode(mode[i]))
        {
            throw std::runtime_error
            (
                failure(path, "event " + std::to_string(i) + " has unknown family code "
                        + std::to_string(family[i]) + " or mode code "
                        + std::to_string(mode[i]))
            );
        }
        BreakEvent e;
        e.time = time[i];
        e.position = Vec3(x[i], y[i], z[i]);
        e.separation = Vec3(dx[i], dy[i], dz[i]);
        e.tagA = tagA[i];
        e.tagB = tagB[i];
        e.family = static_cast<BondFamily>(family[i]);
        e.mode = static_cast<BreakMode>(mode[i]);
        record.events_.push_back(e);
    }
    return record;
}

} // namespace iceDEM
