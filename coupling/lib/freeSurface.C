#include "freeSurface.H"
#include "processorPolyPatch.H"

#include <algorithm>
#include <map>
#include <utility>

namespace Foam
{
namespace iceCoupling
{

freeSurface::freeSurface(const fvMesh& mesh)
:
    mesh_(mesh),
    bottom_(mesh.bounds().min().z()),
    top_(mesh.bounds().max().z()),
    planArea_(0),
    cellBottom_(mesh.nCells()),
    cellHeight_(mesh.nCells())
{
    const pointField& points = mesh.points();
    forAll(cellBottom_, celli)
    {
        scalar lo = GREAT, hi = -GREAT;
        for (const label pointi : mesh.cellPoints()[celli])
        {
            lo = min(lo, points[pointi].z());
            hi = max(hi, points[pointi].z());
        }
        cellBottom_[celli] = lo;
        cellHeight_[celli] = hi - lo;
    }

    // A processor face that is not vertical cuts a column.
    for (const polyPatch& patch : mesh.boundaryMesh())
    {
        if (!isA<processorPolyPatch>(patch))
        {
            continue;
        }
        for (const vector& n : patch.faceNormals())
        {
            if (mag(n.z()) > 1e-6)
            {
                FatalErrorInFunction
                    << "the decomposition cuts a vertical column of cells (patch " << patch.name()
                    << "): with hydrodynamics vof each column must lie on one rank, which reads"
                    << " its water height; decompose in x and y only (system/decomposeParDict,"
                    << " e.g. simpleCoeffs n (2 1 1))" << exit(FatalError);
            }
        }
    }

    // Columns: cells with the same plan position of their centre (to a
    // thousandth of their smallest plan size), sorted bottom up.
    const vectorField& C = mesh.C();
    std::map<std::pair<long, long>, std::vector<std::pair<scalar, label>>> byPlan;
    scalar tolerance = GREAT;
    forAll(C, celli)
    {
        tolerance = min(tolerance, 1e-3*cbrt(mesh.V()[celli]));
    }
    forAll(C, celli)
    {
        const std::pair<long, long> key(std::lround(C[celli].x()/tolerance), std::lround(C[celli].y()/tolerance));
        byPlan[key].emplace_back(C[celli].z(), celli);
    }
    columns_.setSize(byPlan.size());
    label columni = 0;
    for (auto& column : byPlan)
    {
        std::sort(column.second.begin(), column.second.end());
        labelList& cells = columns_[columni];
        cells.setSize(column.second.size());
        forAll(cells, k)
        {
            cells[k] = column.second[k].second;
        }
        planArea_ += mesh.V()[cells[0]]/cellHeight_[cells[0]];
        ++columni;
    }
    reduce(planArea_, sumOp<scalar>());
}


void freeSurface::setLevel(volScalarField& alphaWater, scalar level) const
{
    scalarField& alpha = alphaWater.primitiveFieldRef();
    forAll(alpha, celli)
    {
        alpha[celli] = min(max((level - cellBottom_[celli])/cellHeight_[celli], scalar(0)), scalar(1));
    }
    alphaWater.correctBoundaryConditions();
}


tmp<scalarField> freeSurface::columnHeight(const volScalarField& alphaWater) const
{
    tmp<scalarField> theight(new scalarField(mesh_.nCells()));
    scalarField& height = theight.ref();
    for (const labelList& cells : columns_)
    {
        scalar h = cellBottom_[cells[0]];
        for (const label celli : cells)
        {
            h += alphaWater[celli]*cellHeight_[celli];
        }
        for (const label celli : cells)
        {
            height[celli] = h;
        }
    }
    return theight;
}


scalar freeSurface::freeLevel(const volScalarField& alphaWater, const volScalarField& eps) const
{
    // Sums of area times height and of area, free columns then all columns.
    scalarField sums(4, 0);
    const tmp<scalarField> height(columnHeight(alphaWater));
    for (const labelList& cells : columns_)
    {
        bool free = true;
        for (const label celli : cells)
        {
            free = free && eps[celli] >= 1 - SMALL;
        }
        const scalar area = mesh_.V()[cells[0]]/cellHeight_[cells[0]];
        const scalar h = height()[cells[0]];
        if (free)
        {
            sums[0] += area*h;
            sums[1] += area;
        }
        sums[2] += area*h;
        sums[3] += area;
    }
    Pstream::listCombineGather(sums, plusEqOp<scalar>());
    Pstream::listCombineScatter(sums);
    return sums[1] > 0 ? sums[0]/sums[1] : sums[2]/sums[3];
}


scalar freeSurface::waterVolume(const volScalarField& alphaWater, const volScalarField& eps) const
{
    return gSum(alphaWater.primitiveField()*eps.primitiveField()*mesh_.V());
}

} // namespace iceCoupling
} // namespace Foam
