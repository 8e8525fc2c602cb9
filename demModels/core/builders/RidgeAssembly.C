#include "RidgeAssembly.H"

#include "CellGrid.H"
#include "HydrostaticWater.H"
#include "Percentile.H"
#include "RandomPacking.H"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace iceDEM
{

namespace
{
//- The CL's packing on top of layout.clBottom, as one more block (clBlock).
void addLayer(RidgeLayout& layout, const ConsolidatedLayerSpec& cl);
}

RidgeLayout assembleRidge
(
    const std::vector<SavedParticle>& keel,
    const ConsolidatedLayerSpec& cl,
    double trimDepth
)
{
    if (keel.empty())
    {
        throw std::invalid_argument("assembleRidge: the keel has no particles");
    }
    if (cl.thickness < 0.0 || trimDepth < 0.0)
    {
        throw std::invalid_argument("assembleRidge: CL thickness and trim depth must not be negative");
    }
    RidgeLayout layout;
    std::vector<double> tops, bottoms;
    int maxBlock = -1;
    for (const SavedParticle& p : keel)
    {
        tops.push_back(p.position.z() + p.radius);
        bottoms.push_back(p.position.z() - p.radius);
        maxBlock = std::max(maxBlock, p.block);
    }
    layout.keelTop = percentile(tops, 0.99);
    layout.keelBottom = percentile(bottoms, 0.01);

    const bool withLayer = cl.thickness > 0.0;
    const double trimAbove = withLayer ? layout.keelTop - trimDepth : HUGE_VAL;
    double highestKept = -HUGE_VAL;
    for (std::size_t k = 0; k < keel.size(); ++k)
    {
        const SavedParticle& p = keel[k];
        if (p.position.z() > trimAbove)
        {
            ++layout.trimmedParticles;
            continue;
        }
        ParticleSpec s;
        s.position = p.position;
        s.radius = p.radius;
        s.block = p.block;
        s.fixed = p.type != 1;
        layout.particles.push_back(s);
        layout.keelTagOfParticle.push_back(static_cast<long>(k) + 1);
        highestKept = std::max(highestKept, p.position.z() + p.radius);
    }
    layout.keelParticles = static_cast<int>(layout.particles.size());
    if (!withLayer)
    {
        layout.clBottom = layout.clTop = highestKept;
        return layout;
    }

    layout.clBlock = maxBlock + 1;
    layout.clBottom = highestKept;
    addLayer(layout, cl);
    return layout;
}


RidgeLayout assembleLayerAlone(const ConsolidatedLayerSpec& cl, double bottom)
{
    if (!(cl.thickness > 0.0))
    {
        throw std::invalid_argument("assembleLayerAlone: the CL must have a positive thickness");
    }
    RidgeLayout layout;
    layout.keelTop = layout.keelBottom = bottom;
    layout.clBlock = 0;
    layout.clBottom = bottom;
    addLayer(layout, cl);
    return layout;
}


namespace
{
void addLayer(RidgeLayout& layout, const ConsolidatedLayerSpec& cl)
{
    layout.clTop = layout.clBottom + cl.thickness;
    RandomPackingSpec spec;
    spec.lo = Vec3(0.0, 0.0, layout.clBottom);
    spec.hi = Vec3(cl.length, cl.width, layout.clTop);
    spec.particleCount =
        particleCountForDiameter(spec.lo, spec.hi, cl.particleDiameter, cl.radiusSpread, cl.solidFraction);
    spec.radiusSpread = cl.radiusSpread;
    spec.targetSolidFraction = cl.solidFraction;
    spec.seed = cl.seed;
    for (ParticleSpec p : buildRandomPacking(spec))
    {
        p.block = layout.clBlock;
        p.fixed = false;
        layout.particles.push_back(p);
        layout.keelTagOfParticle.push_back(-1);
    }
}
} // namespace


RidgeGeometry measureRidge(const std::vector<SavedParticle>& particles, int layerBlock, double length, double width)
{
    std::vector<double> keelLows, keelHighs, layerLows, layerHighs;
    double meanRadius = 0.0;
    for (const SavedParticle& p : particles)
    {
        const bool inLayer = layerBlock >= 0 && p.block == layerBlock;
        (inLayer ? layerLows : keelLows).push_back(p.position.z() - p.radius);
        (inLayer ? layerHighs : keelHighs).push_back(p.position.z() + p.radius);
        meanRadius += p.radius / particles.size();
    }
    if (keelLows.empty() && layerLows.empty())
    {
        throw std::invalid_argument("measureRidge: no particles");
    }
    RidgeGeometry g;
    g.length = length;
    g.width = width;
    g.keelParticles = static_cast<int>(keelLows.size());
    g.particleRadius = meanRadius;
    g.layerParticles = static_cast<int>(layerLows.size());
    if (keelLows.empty())   // a layer alone
    {
        g.clBottom = percentile(layerLows, 0.01);
        g.clTop = percentile(layerHighs, 0.99);
        g.keelBottom = g.keelTop = g.clBottom;
        return g;
    }
    g.keelBottom = percentile(keelLows, 0.01);
    g.keelTop = percentile(keelHighs, 0.99);
    g.clBottom = g.hasLayer() ? percentile(layerLows, 0.01) : g.keelTop;
    g.clTop = g.hasLayer() ? percentile(layerHighs, 0.99) : g.keelTop;
    return g;
}


double floatingWaterLevel(const std::vector<ParticleSpec>& particles, double densityRatio)
{
    double bottom = HUGE_VAL;
    for (const ParticleSpec& p : particles)
    {
        bottom = std::min(bottom, p.position.z() - p.radius);
    }
    return bottom + levelDraft(particles, densityRatio);
}


OverlapStatistics overlapStatistics(const std::vector<ParticleSpec>& particles, const std::vector<Vec3>& positions)
{
    if (positions.size() != particles.size())
    {
        throw std::invalid_argument("overlapStatistics: one position per particle expected");
    }
    OverlapStatistics stats;
    if (particles.empty())
    {
        return stats;
    }
    double maxRadius = 0.0;
    for (const ParticleSpec& p : particles)
    {
        maxRadius = std::max(maxRadius, p.radius);
    }
    double sum = 0.0;
    CellGrid::around(positions, 2.0 * maxRadius).forEachPair([&](int a, int b)
    {
        if (particles[a].block == particles[b].block)
        {
            return;
        }
        const double overlap = particles[a].radius + particles[b].radius - (positions[b] - positions[a]).norm();
        if (overlap > 0.0)
        {
            ++stats.touchingPairs;
            sum += overlap;
            stats.maxOverlap = std::max(stats.maxOverlap, overlap);
        }
    });
    stats.meanOverlap = stats.touchingPairs > 0 ? sum / stats.touchingPairs : 0.0;
    return stats;
}

} // namespace iceDEM
