#include "LayerDisplacementTest.H"

#include "CsvWriter.H"
#include "IceBondForces.H"
#include "LiggghtsInstance.H"
#include "PlatenLoading.H"
#include "ParticleGather.H"

#include <utility>

namespace iceDEM
{

LayerDisplacementTest::LayerDisplacementTest(std::string name, Axis axis)
:
    name_(std::move(name)),
    axis_(axis)
{}


int LayerDisplacementTest::particleType(int, bool inLayer) const
{
    // Neither keel nor layer is integrated; the layer keeps the integrated
    // type because LIGGGHTS' granular models need one.
    return inLayer ? mobileType : fixedType;
}


double LayerDisplacementTest::force(const LiggghtsInstance& lmp, MPI_Comm comm, long layerFirstTag) const
{
    // What the actuator holding the layer must apply: minus the net force of
    // bonds, contacts, gravity and water on the layer's particles.
    return -netForceOnTagsFrom(lmp, comm, layerFirstTag, static_cast<int>(axis_));
}


std::vector<double> LayerDisplacementTest::curveValues
(
    const IceBondForces& bonds, MPI_Comm comm, long layerFirstTag
) const
{
    // The actuator balances the bonds' pull on the layer: minus it.
    const double local = -bonds.localForceAcross(layerFirstTag)[static_cast<int>(axis_)];
    return {sumOverRanks(comm, local)};
}


void LayerDisplacementTest::startMotion(LiggghtsInstance& lmp, const std::string& speed, const std::string& travel) const
{
    lmp.command("variable layerV equal " + speed);
    lmp.command("variable layerD equal " + travel);
    // Every component given: a NULL one would be integrated from the forces.
    lmp.command(axis_ == Axis::z
        ? "fix moveLayer layer move variable v_zero v_zero v_layerD v_zero v_zero v_layerV"
        : "fix moveLayer layer move variable v_layerD v_zero v_zero v_layerV v_zero v_zero");
}


void LayerDisplacementTest::addFigures
(
    Json& j, const RidgeGeometry& g, const CsvWriter& curve, double peak, double startForce
) const
{
    const double area = g.length * g.width;
    j["interface_area_m2"] = area;
    j["interface_strength_Pa"] = (peak - startForce) / area;

    if (curve.nRows() == 0)
    {
        return;
    }
    const std::size_t column = curve.columnIndex("interfaceBondForce");
    const std::size_t atPeak = curve.rowOfLargest(column);
    const double bondPeak = curve.row(atPeak)[column];
    j["interface_bond_peak_N"] = bondPeak;
    j["interface_bond_force_at_start_N"] = curve.row(0)[column];
    j["travel_at_interface_bond_peak_m"] = curve.row(atPeak)[PlatenLoading::travelColumn];
    j["interface_bond_strength_Pa"] = (bondPeak - curve.row(0)[column]) / area;
}

} // namespace iceDEM
