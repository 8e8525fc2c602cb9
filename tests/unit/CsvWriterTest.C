#include "CsvWriter.H"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace iceDEM;

namespace
{

std::string contents(const fs::path& file)
{
    std::ifstream in(file);
    std::stringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

fs::path scratchFolder(const std::string& name)
{
    const fs::path dir = fs::temp_directory_path()
                       / ("iceDEM_Csv_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

} // namespace


TEST(CsvWriter, HeaderAndRowsWithTenSignificantDigits)
{
    CsvWriter table({"time", "displacement", "force"});
    table.addRow({0.0, 1.0e-3, 1234.5678901234});
    table.addRow({0.1, -2.5e-7, 1.0/3.0});
    EXPECT_EQ(table.nRows(), 2u);
    EXPECT_EQ
    (
        table.text(),
        "time,displacement,force\n"
        "0,0.001,1234.56789\n"
        "0.1,-2.5e-07,0.3333333333\n"
    );
}


TEST(CsvWriter, NonFiniteValuesAreReadable)
{
    CsvWriter table({"a", "b", "c"});
    const double inf = std::numeric_limits<double>::infinity();
    table.addRow({std::nan(""), inf, -inf});
    EXPECT_EQ(table.text(), "a,b,c\nnan,inf,-inf\n");
}


TEST(CsvWriter, RejectsBadColumnsAndRows)
{
    EXPECT_THROW(CsvWriter({}), std::invalid_argument);
    EXPECT_THROW(CsvWriter({"a", ""}), std::invalid_argument);
    EXPECT_THROW(CsvWriter({"a", "a"}), std::invalid_argument);
    EXPECT_THROW(CsvWriter({"a,b"}), std::invalid_argument);
    CsvWriter table({"a", "b"});
    EXPECT_THROW(table.addRow({1.0}), std::invalid_argument);
    EXPECT_THROW(table.addRow({1.0, 2.0, 3.0}), std::invalid_argument);
    EXPECT_EQ(table.nRows(), 0u);
}


TEST(CsvWriter, EachWriteRewritesTheWholeFile)
{
    const fs::path dir = scratchFolder("rewrite");
    const fs::path file = dir/"postProcessing"/"platenForce.csv";
    CsvWriter table({"time", "force"});
    table.write(file.string());
    EXPECT_EQ(contents(file), "time,force\n");
    table.addRow({1.0, 2.0});
    table.write(file.string());
    table.addRow({2.0, 4.0});
    table.write(file.string());
    EXPECT_EQ(contents(file), "time,force\n1,2\n2,4\n");
    std::size_t nFiles = 0;
    for (const auto& entry : fs::directory_iterator(file.parent_path()))
    {
        nFiles += entry.is_regular_file();
    }
    EXPECT_EQ(nFiles, 1u);
    fs::remove_all(dir);
}


TEST(CsvWriter, FindsColumnsByNameAndTheFirstRowOfAColumnsLargestValue)
{
    CsvWriter table({"travel", "force"});
    EXPECT_EQ(table.columnIndex("force"), 1u);
    EXPECT_THROW(table.columnIndex("reaction"), std::invalid_argument);
    EXPECT_THROW(table.rowOfLargest(1), std::out_of_range);
    table.addRow({0.0, 2.0});
    table.addRow({1.0, 5.0});
    table.addRow({2.0, 3.0});
    table.addRow({3.0, 5.0});
    EXPECT_EQ(table.rowOfLargest(1), 1u);   // the first of two equal maxima
    EXPECT_EQ(table.rowOfLargest(0), 3u);
    EXPECT_THROW(table.rowOfLargest(2), std::out_of_range);
}
