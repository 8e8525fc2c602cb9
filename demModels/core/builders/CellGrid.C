#include "CellGrid.H"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace iceDEM
{

CellGrid::CellGrid(const Vec3& lo, const Vec3& hi, double minCellSize, double maxCells)
:
    lo_(lo)
{
    const Vec3 extent = hi - lo;
    double size = minCellSize;
    while (true)
    {
        double cells = 1.0;
        for (int k = 0; k < 3; ++k)
        {
            n_[k] = std::max(1L, static_cast<long>(std::floor(extent[k]/size)));
            cells *= n_[k];
        }
        if (cells <= maxCells)
        {
            break;
        }
        size *= 2.0;
    }
    for (int k = 0; k < 3; ++k)
    {
        invSize_[k] = extent[k] > 0.0 ? n_[k]/extent[k] : 0.0;
    }
}


CellGrid CellGrid::around(const std::vector<Vec3>& points, double minCellSize)
{
    if (points.empty())
    {
        throw std::invalid_argument("CellGrid::around: no points");
    }
    Vec3 lo = points.front(), hi = lo;
    for (const Vec3& p : points)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    CellGrid grid(lo, hi, minCellSize, 8.0*points.size() + 64.0);
    grid.build(points);
    return grid;
}


void CellGrid::build(const std::vector<Vec3>& positions)
{
    const long nCells = n_[0]*n_[1]*n_[2];
    cellOf_.resize(positions.size());
    start_.assign(nCells + 1, 0);
    for (std::size_t i = 0; i < positions.size(); ++i)
    {
        cellOf_[i] = cellIndex(positions[i]);
        ++start_[cellOf_[i] + 1];
    }
    for (long c = 0; c < nCells; ++c)
    {
        start_[c + 1] += start_[c];
    }
    items_.resize(positions.size());
    std::vector<long> next(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < positions.size(); ++i)
    {
        items_[next[cellOf_[i]]++] = static_cast<int>(i);
    }
}


long CellGrid::cellIndex(const Vec3& p) const
{
    long c[3];
    for (int k = 0; k < 3; ++k)
    {
        c[k] = std::min(n_[k] - 1, std::max(0L, static_cast<long>((p[k] - lo_[k])*invSize_[k])));
    }
    return index(c[0], c[1], c[2]);
}

} // namespace iceDEM
