#include "CsvWriter.H"

#include "AtomicFile.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace iceDEM
{

namespace
{

void checkColumnName(const std::string& name, const std::vector<std::string>& earlier)
{
    if (name.empty())
    {
        throw std::invalid_argument("CsvWriter: empty column name");
    }
    if (name.find_first_of(",\"\r\n") != std::string::npos)
    {
        throw std::invalid_argument("CsvWriter: column name '" + name
                                    + "' contains a comma, quote or line break");
    }
    if (std::find(earlier.begin(), earlier.end(), name) != earlier.end())
    {
        throw std::invalid_argument("CsvWriter: duplicate column name '" + name + "'");
    }
}

void appendValue(std::string& text, double value)
{
    if (std::isnan(value))
    {
        text += "nan";
        return;
    }
    if (std::isinf(value))
    {
        text += value > 0 ? "inf" : "-inf";
        return;
    }
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.10g", value);
    text += buffer;
}

} // namespace


CsvWriter::CsvWriter(std::vector<std::string> columns)
{
    if (columns.empty())
    {
        throw std::invalid_argument("CsvWriter: no columns");
    }
    for (const std::string& name : columns)
    {
        checkColumnName(name, columns_);
        columns_.push_back(name);
    }
}


void CsvWriter::addRow(const std::vector<double>& values)
{
    if (values.size() != columns_.size())
    {
        throw std::invalid_argument
        (
            "CsvWriter: row has " + std::to_string(values.size()) + " values, table has "
          + std::to_string(columns_.size()) + " columns"
        );
    }
    rows_.push_back(values);
}


std::size_t CsvWriter::columnIndex(const std::string& name) const
{
    const auto found = std::find(columns_.begin(), columns_.end(), name);
    if (found == columns_.end())
    {
        throw std::invalid_argument("CsvWriter: no column '" + name + "'");
    }
    return static_cast<std::size_t>(found - columns_.begin());
}


std::size_t CsvWriter::rowOfLargest(std::size_t column) const
{
    if (rows_.empty())
    {
        throw std::out_of_range("CsvWriter: no rows");
    }
    std::size_t largest = 0;
    for (std::size_t k = 1; k < rows_.size(); ++k)
    {
        if (rows_[k].at(column) > rows_[largest].at(column)) largest = k;
    }
    return largest;
}


std::string CsvWriter::text() const
{
    std::string text;
    for (std::size_t c = 0; c < columns_.size(); ++c)
    {
        text += (c ? "," : "") + columns_[c];
    }
    text += '\n';
    for (const std::vector<double>& values : rows_)
    {
        for (std::size_t c = 0; c < values.size(); ++c)
        {
            if (c)
            {
                text += ',';
            }
            appendValue(text, values[c]);
        }
        text += '\n';
    }
    return text;
}


void CsvWriter::write(const std::string& path) const
{
    writeFileAtomically(path, text());
}

} // namespace iceDEM
