#include "RubbleBuilder.H"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace iceDEM
{

namespace
{

//- Axis-aligned extent of a set of sphere centres grown by a radius.
struct Envelope
{
    Vec3 lo, hi;
};

Envelope envelope(const std::vector<Vec3>& centres, double radius)
{
    Envelope b{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
    for (const Vec3& c : centres)
    {
        b.lo = b.lo.cwiseMin(c - Vec3::Constant(radius));
        b.hi = b.hi.cwiseMax(c + Vec3::Constant(radius));
    }
    return b;
}

//- Tilts the block by `angle` about the horizontal axis at `direction` through its centroid.
std::vector<Vec3> tilted(std::vector<Vec3> centres, double direction, double angle)
{
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& c : centres) centroid += c;
    centroid /= static_cast<double>(centres.size());
    const Eigen::AngleAxisd rotation(angle, Vec3(std::cos(direction), std::sin(direction), 0.0));
    for (Vec3& c : centres)
    {
        c = centroid + rotation*(c - centroid);
    }
    return centres;
}

double perimeter(const PlanPolygon& p)
{
    double sum = 0.0;
    const auto& v = p.vertices();
    for (std::size_t k = 0; k < v.size(); ++k)
    {
        sum += (v[(k + 1) % v.size()] - v[k]).norm();
    }
    return sum;
}

} // namespace


Rubble buildRubble(const RubbleSpec& spec, const BlockSizeSource& sizes)
{
    if (!(spec.iceVolume > 0.0 && spec.boxLength > 0.0 && spec.boxWidth > 0.0 && spec.particleDiameter > 0.0))
    {
        throw std::invalid_argument("buildRubble: need positive ice volume, box and particle diameter");
    }
    std::mt19937_64 rng(spec.seed);
    std::uniform_real_distribution<double> turn(0.0, 2.0*M_PI);
    std::uniform_real_distribution<double> tilt(-spec.maxTilt, spec.maxTilt);
    const double r = 0.5*spec.particleDiameter;
    const double gap = 0.1*r;   // between neighbouring envelopes in a row

    Rubble rubble;
    rubble.blockThickness = hcpThickness(spec.particleDiameter, spec.layers);
    double x = 0.0, y = 0.0, rowDepth = 0.0, sheetHeight = 0.0;
    double base = spec.firstSheetBase;
    while (rubble.iceVolume < spec.iceVolume)
    {
        const BlockSize size = sizes.draw(rng);
        const PlanPolygon local = blockOutline(size, spec.shape, rng);
        // A long block in a narrow box is turned again until it fits.
        constexpr int turnsToTry = 16;
        PlanPolygon turned;
        std::vector<Vec3> flat, centres;
        Envelope box;
        Vec3 extent;
        bool fits = false;
        for (int attempt = 0; attempt < turnsToTry && !fits; ++attempt)
        {
            turned = local.rotated(turn(rng));
            flat = hcpBlockCentres(turned, spec.particleDiameter, spec.layers);
            if (flat.empty())
            {
                break;
            }
            const double tiltDirection = turn(rng);
            centres = tilted(flat, tiltDirection, tilt(rng));
            box = envelope(centres, r);
            extent = box.hi - box.lo;
            fits = extent.x() <= spec.boxLength && extent.y() <= spec.boxWidth;
        }
        if (flat.empty())
        {
            continue;
        }
        if (!fits)
        {
            throw std::invalid_argument("buildRubble: a block of " + std::to_string(size.length) + " x "
                + std::to_string(size.width) + " m fits the " + std::to_string(spec.boxLength) + " x "
                + std::to_string(spec.boxWidth) + " m box in none of " + std::to_string(turnsToTry) + " orientations");
        }
        if (x + extent.x() > spec.boxLength)
        {
            x = 0.0;
            y += rowDepth + gap;
            rowDepth = 0.0;
        }
        if (y + extent.y() > spec.boxWidth)
        {
            x = y = rowDepth = 0.0;
            base += sheetHeight + spec.sheetGap;
            sheetHeight = 0.0;
        }
        const Vec3 shift = Vec3(x, y, base) - box.lo;
        BuiltBlock block;
        block.outline = turned.translated(shift.head<2>());
        block.planArea = turned.area();
        block.volume = block.planArea*rubble.blockThickness;
        block.surface = 2.0*block.planArea + perimeter(turned)*rubble.blockThickness;
        block.firstParticle = static_cast<int>(rubble.particles.size());
        block.particleCount = static_cast<int>(centres.size());
        const int id = static_cast<int>(rubble.blocks.size());
        for (const Vec3& c : centres)
        {
            ParticleSpec p;
            p.position = c + shift;
            p.radius = r;
            p.block = id;
            rubble.particles.push_back(p);
            rubble.sphereVolume += 4.0/3.0*M_PI*r*r*r;
        }
        rubble.blocks.push_back(block);
        rubble.iceVolume += block.volume;
        x += extent.x() + gap;
        rowDepth = std::max(rowDepth, extent.y());
        sheetHeight = std::max(sheetHeight, extent.z());
    }
    return rubble;
}

} // namespace iceDEM
