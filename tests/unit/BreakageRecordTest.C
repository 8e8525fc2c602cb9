#include "BreakageRecord.H"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace iceDEM;

namespace
{

BreakEvent event
(
    double time,
    long tagA,
    long tagB,
    BondFamily family,
    BreakMode mode,
    const Vec3& position = Vec3(0.1, -0.2, 0.3)
)
{
    BreakEvent e;
    e.time = time;
    e.position = position;
    e.separation = Vec3(0.02, -time, 1e-3*tagA);
    e.tagA = tagA;
    e.tagB = tagB;
    e.family = family;
    e.mode = mode;
    return e;
}

BreakageRecord mixedRecord()
{
    BreakageRecord record;
    record.append(event(2.5, 7, 9, BondFamily::ice, BreakMode::tension, Vec3(1.0/3, 2, -3)));
    record.append(event(0.125, 12, 13, BondFamily::freeze, BreakMode::shear));
    record.append(event(2.5, 3, 4, BondFamily::ice, BreakMode::bending));
    record.append(event(1.0, 5000000000L, 5000000001L, BondFamily::freeze, BreakMode::twist,
                        Vec3(-1e-9, 1e9, 0.0)));
    record.append(event(2.5, 3, 2, BondFamily::ice, BreakMode::tension));
    return record;
}

class BreakageRecordFile : public ::testing::Test
{
protected:
    void SetUp() override
    {
        const std::string name =
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path()
             / ("iceDEM_Breakage_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
    }

    void TearDown() override
    {
        fs::remove_all(dir_);
    }

    std::string path(const std::string& relative) const
    {
        return (dir_/relative).string();
    }

    fs::path dir_;
};

std::string stringAttribute(hid_t group, const char* name)
{
    const hid_t attribute = H5Aopen(group, name, H5P_DEFAULT);
    EXPECT_GE(attribute, 0) << name;
    const hid_t type = H5Aget_type(attribute);
    std::string value(H5Tget_size(type), '\0');
    H5Aread(attribute, type, value.data());
    H5Tclose(type);
    H5Aclose(attribute);
    return value.substr(0, value.find('\0'));
}

std::int64_t countAttribute(hid_t group)
{
    const hid_t attribute = H5Aopen(group, "count", H5P_DEFAULT);
    EXPECT_GE(attribute, 0);
    std::int64_t count = -1;
    H5Aread(attribute, H5T_NATIVE_INT64, &count);
    H5Aclose(attribute);
    return count;
}

} // namespace


TEST(BreakageRecord, CountsByModeAndFamily)
{
    const BreakageRecord record = mixedRecord();
    EXPECT_EQ(record.size(), 5u);
    EXPECT_EQ(record.count(BreakMode::tension), 2u);
    EXPECT_EQ(record.count(BreakMode::shear), 1u);
    EXPECT_EQ(record.count(BreakMode::twist), 1u);
    EXPECT_EQ(record.count(BreakMode::bending), 1u);
    EXPECT_EQ(record.count(BondFamily::ice), 3u);
    EXPECT_EQ(record.count(BondFamily::freeze), 2u);
    EXPECT_EQ(record.count(BondFamily::ice, BreakMode::tension), 2u);
    EXPECT_EQ(record.count(BondFamily::freeze, BreakMode::tension), 0u);
    EXPECT_EQ(record.count(BondFamily::freeze, BreakMode::twist), 1u);
}


TEST(BreakageRecord, SortsByTimeThenTags)
{
    BreakageRecord record = mixedRecord();
    record.sort();
    const auto& e = record.events();
    ASSERT_EQ(e.size(), 5u);
    EXPECT_EQ(e[0].time, 0.125);
    EXPECT_EQ(e[1].time, 1.0);
    EXPECT_EQ(e[2].tagA, 3);
    EXPECT_EQ(e[2].tagB, 2);
    EXPECT_EQ(e[3].tagA, 3);
    EXPECT_EQ(e[3].tagB, 4);
    EXPECT_EQ(e[4].tagA, 7);
}


TEST(BreakageRecord, RejectsEventWithoutBreakMode)
{
    BreakageRecord record;
    EXPECT_THROW(record.append(event(0.0, 1, 2, BondFamily::ice, BreakMode::none)),
                 std::invalid_argument);
    EXPECT_THROW(record.append(event(0.0, 1, 2, static_cast<BondFamily>(2),
                                     BreakMode::shear)),
                 std::invalid_argument);
    EXPECT_TRUE(record.empty());
}


TEST_F(BreakageRecordFile, WriteThenReadGivesSortedEventsExactly)
{
    const BreakageRecord written = mixedRecord();
    written.writeHdf5(path("out/breakage.h5"));

    const BreakageRecord read = BreakageRecord::readHdf5(path("out/breakage.h5"));
    BreakageRecord expected = written;
    expected.sort();
    ASSERT_EQ(read.size(), expected.size());
    for (std::size_t i = 0; i < read.size(); ++i)
    {
        EXPECT_EQ(read.events()[i], expected.events()[i]) << "event " << i;
    }
    EXPECT_EQ(read.events()[1].tagA, 5000000000L);
    EXPECT_EQ(read.events()[1].position, Vec3(-1e-9, 1e9, 0.0));
    EXPECT_EQ(read.events()[1].separation, Vec3(0.02, -1.0, 5e6));

    // Only the final file is left in the folder.
    std::size_t nFiles = 0;
    for (const auto& entry : fs::directory_iterator(path("out")))
    {
        nFiles += entry.is_regular_file();
    }
    EXPECT_EQ(nFiles, 1u);
}


TEST_F(BreakageRecordFile, LayoutAndAttributes)
{
    mixedRecord().writeHdf5(path("breakage.h5"));

    const hid_t file = H5Fopen(path("breakage.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t group = H5Gopen2(file, "/breakage", H5P_DEFAULT);
    ASSERT_GE(group, 0);
    EXPECT_EQ(stringAttribute(group, "familyCodes"), "0=ice,1=freeze");
    EXPECT_EQ(stringAttribute(group, "modeCodes"), "1=tension,2=shear,3=twist,4=bending");
    EXPECT_EQ(countAttribute(group), 5);

    const std::pair<const char*, hid_t> datasets[] =
    {
        {"time", H5T_IEEE_F64LE}, {"x", H5T_IEEE_F64LE}, {"y", H5T_IEEE_F64LE},
        {"z", H5T_IEEE_F64LE}, {"dx", H5T_IEEE_F64LE}, {"dy", H5T_IEEE_F64LE},
        {"dz", H5T_IEEE_F64LE}, {"tagA", H5T_STD_I64LE}, {"tagB", H5T_STD_I64LE},
        {"family", H5T_STD_I32LE}, {"mode", H5T_STD_I32LE}
    };
    for (const auto& [name, expectedType] : datasets)
    {
        const hid_t dataset = H5Dopen2(group, name, H5P_DEFAULT);
        ASSERT_GE(dataset, 0) << name;
        const hid_t type = H5Dget_type(dataset);
        EXPECT_GT(H5Tequal(type, expectedType), 0) << name;
        const hid_t space = H5Dget_space(dataset);
        hsize_t n = 0;
        EXPECT_EQ(H5Sget_simple_extent_ndims(space), 1) << name;
        H5Sget_simple_extent_dims(space, &n, nullptr);
        EXPECT_EQ(n, 5u) << name;
        H5Sclose(space);
        H5Tclose(type);
        H5Dclose(dataset);
    }
    H5Gclose(group);
    H5Fclose(file);
}


TEST_F(BreakageRecordFile, ZeroEvents)
{
    BreakageRecord().writeHdf5(path("empty.h5"));
    const BreakageRecord read = BreakageRecord::readHdf5(path("empty.h5"));
    EXPECT_TRUE(read.empty());

    const hid_t file = H5Fopen(path("empty.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t group = H5Gopen2(file, "/breakage", H5P_DEFAULT);
    ASSERT_GE(group, 0);
    EXPECT_EQ(countAttribute(group), 0);
    H5Gclose(group);
    H5Fclose(file);
}


TEST_F(BreakageRecordFile, RewriteReplacesTheFile)
{
    BreakageRecord record = mixedRecord();
    record.writeHdf5(path("breakage.h5"));
    record.append(event(3.0, 20, 21, BondFamily::ice, BreakMode::shear));
    record.writeHdf5(path("breakage.h5"));
    EXPECT_EQ(BreakageRecord::readHdf5(path("breakage.h5")).size(), 6u);
}


TEST_F(BreakageRecordFile, MissingFileOrGroupNamesThePath)
{
    try
    {
        BreakageRecord::readHdf5(path("missing.h5"));
        FAIL() << "expected std::runtime_error";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(path("missing.h5")), std::string::npos);
    }

    fs::create_directories(dir_);
    const hid_t file = H5Fcreate(path("other.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT,
                                 H5P_DEFAULT);
    H5Fclose(file);
    EXPECT_THROW(BreakageRecord::readHdf5(path("other.h5")), std::runtime_error);
}
