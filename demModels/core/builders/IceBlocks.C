#include "IceBlocks.H"

#include "InputError.H"

#include <cmath>
#include <fstream>
#include <sstream>

namespace iceDEM
{

BlockSizeSource BlockSizeSource::synthetic(const Synthetic& p)
{
    if (!(p.minWidth > 0.0 && p.maxWidth >= p.minWidth
       && p.minAspect >= 1.0 && p.maxAspect >= p.minAspect
       && p.minAreaFraction > 0.0 && p.maxAreaFraction <= 1.0 && p.maxAreaFraction >= p.minAreaFraction))
    {
        throw std::invalid_argument("BlockSizeSource::synthetic: inconsistent ranges");
    }
    BlockSizeSource s;
    s.params_ = p;
    return s;
}


BlockSizeSource BlockSizeSource::fromCsv(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
    {
        throw InputError(path, "", "cannot open the block size file");
    }
    BlockSizeSource s;
    s.synthetic_ = false;
    std::string line;
    int lineNo = 0;
    bool header = false;
    while (std::getline(in, line))
    {
        ++lineNo;
        if (line.empty() || line[0] == '#')
        {
            continue;
        }
        if (!header)
        {
            if (line.rfind("length_m,width_m,plan_area_m2", 0) != 0)
            {
                throw InputError(path, "line " + std::to_string(lineNo),
                    "expected the header 'length_m,width_m,plan_area_m2'");
            }
            header = true;
            continue;
        }
        std::istringstream row(line);
        BlockSize b;
        char c1 = 0, c2 = 0;
        row >> b.length >> c1 >> b.width >> c2 >> b.planArea;
        if (!row || c1 != ',' || c2 != ',')
        {
            throw InputError(path, "line " + std::to_string(lineNo), "expected three numbers separated by commas");
        }
        if (!(b.width > 0.0 && b.length >= b.width && b.planArea > 0.0
           && b.planArea <= b.length*b.width*(1.0 + 1e-9)))
        {
            throw InputError(path, "line " + std::to_string(lineNo),
                "need length_m >= width_m > 0 and 0 < plan_area_m2 <= length_m * width_m");
        }
        s.rows_.push_back(b);
    }
    if (s.rows_.empty())
    {
        throw InputError(path, "", "no block sizes in the file");
    }
    return s;
}


BlockSize BlockSizeSource::draw(std::mt19937_64& rng) const
{
    if (!synthetic_)
    {
        std::uniform_int_distribution<std::size_t> pick(0, rows_.size() - 1);
        return rows_[pick(rng)];
    }
    std::uniform_real_distribution<double> u(0.0, 1.0);
    BlockSize b;
    b.width = params_.minWidth + (params_.maxWidth - params_.minWidth)*u(rng);
    b.length = b.width*(params_.minAspect + (params_.maxAspect - params_.minAspect)*u(rng));
    b.planArea = b.length*b.width
       *(params_.minAreaFraction + (params_.maxAreaFraction - params_.minAreaFraction)*u(rng));
    return b;
}


BlockShape blockShapeFromName(const std::string& n, const std::string& file, const std::string& entry)
{
    if (!blockShapeNames.found(n))
    {
        std::string allowed;
        for (const std::string& a : blockShapeNames.names()) allowed += " " + a;
        throw InputError(file, entry, "unknown block shape '" + n + "'; allowed:" + allowed);
    }
    return blockShapeNames.value(n);
}


std::string name(BlockShape s)
{
    return blockShapeNames.name(s);
}


PlanPolygon blockOutline(const BlockSize& size, BlockShape shape, std::mt19937_64& rng)
{
    PlanPolygon outline = PlanPolygon::rectangle(size.length, size.width)
        .translated(Vec2(-0.5*size.length, -0.5*size.width));
    if (shape == BlockShape::cuboid)
    {
        return outline;
    }
    std::uniform_real_distribution<double> angle(0.0, 2.0*M_PI);
    std::uniform_real_distribution<double> depth(0.05, 0.35);
    const double target = size.planArea;
    for (int cut = 0; cut < 1000 && outline.area() > target*(1.0 + 1e-9); ++cut)
    {
        // A plane whose normal points away from the centroid, at a random
        // fraction of the way from the farthest vertex towards the centroid.
        const double a = angle(rng);
        const Vec2 n(std::cos(a), std::sin(a));
        const Vec2 c = outline.centroid();
        double reach = 0.0;
        for (const Vec2& v : outline.vertices())
        {
            reach = std::max(reach, (v - c).dot(n));
        }
        double offset = reach*(1.0 - depth(rng));
        if (outline.clipped(c + offset*n, n).area() < target)
        {
            // This cut would remove too much: place it where it leaves the target area.
            double lo = offset, hi = reach;
            for (int it = 0; it < 100; ++it)
            {
                const double mid = 0.5*(lo + hi);
                (outline.clipped(c + mid*n, n).area() < target ? lo : hi) = mid;
            }
            offset = hi;
        }
        outline = outline.clipped(c + offset*n, n);
    }
    return outline.translated(-outline.centroid());
}


double hcpThickness(double diameter, int layers)
{
    return diameter + (layers - 1)*diameter*std::sqrt(2.0/3.0);
}


double hcpCellArea(double diameter)
{
    return diameter*diameter*std::sqrt(3.0)/2.0;
}


std::vector<Vec3> hcpBlockCentres(const PlanPolygon& outline, double diameter, int layers)
{
    if (!(diameter > 0.0) || layers < 1)
    {
        throw std::invalid_argument("hcpBlockCentres: need diameter > 0 and layers >= 1");
    }
    Vec2 lo = outline.vertices().front(), hi = lo;
    for (const Vec2& v : outline.vertices())
    {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double d = diameter;
    const double rowSpacing = d*std::sqrt(3.0)/2.0;
    const double layerSpacing = d*std::sqrt(2.0/3.0);
    // Lattice anchored half a cell inside the outline's lower-left corner.
    const Vec2 origin = lo + Vec2(0.5*d, 0.5*rowSpacing);
    std::vector<Vec3> centres;
    for (int layer = 0; layer < layers; ++layer)
    {
        const Vec2 shift = (layer % 2 == 0) ? Vec2(0, 0) : Vec2(0.5*d, d/(2.0*std::sqrt(3.0)));
        const double z = 0.5*d + layer*layerSpacing;
        const int rows = static_cast<int>(std::ceil((hi.y() - lo.y())/rowSpacing)) + 2;
        const int cols = static_cast<int>(std::ceil((hi.x() - lo.x())/d)) + 2;
        for (int j = -1; j < rows; ++j)
        {
            for (int i = -1; i < cols; ++i)
            {
                const Vec2 p = origin + shift + Vec2(i*d + (j % 2 != 0 ? 0.5*d : 0.0), j*rowSpacing);
                if (outline.contains(p))
                {
                    centres.emplace_back(p.x(), p.y(), z);
                }
            }
        }
    }
    return centres;
}

} // namespace iceDEM
