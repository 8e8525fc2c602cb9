#include "RidgeLoadTest.H"

#include "PlatenFlexureTest.H"
#include "LayerDisplacementTest.H"

#include <stdexcept>

namespace iceDEM
{

const std::vector<std::string>& RidgeLoadTest::names()
{
    static const std::vector<std::string> all{"flexure", "pullUp", "directShear"};
    return all;
}


std::unique_ptr<RidgeLoadTest> RidgeLoadTest::New(const std::string& name, const RidgeSettings& settings)
{
    if (name == "flexure") return std::make_unique<PlatenFlexureTest>(settings);
    if (name == "pullUp") return std::make_unique<LayerDisplacementTest>(name, LayerDisplacementTest::Axis::z);
    if (name == "directShear") return std::make_unique<LayerDisplacementTest>(name, LayerDisplacementTest::Axis::x);
    throw std::invalid_argument("unknown ridge load test '" + name + "'");
}

} // namespace iceDEM
