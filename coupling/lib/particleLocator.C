#include "particleLocator.H"
#include "Pstream.H"

namespace Foam
{
namespace iceCoupling
{

particleLocator::particleLocator
(
    const fvMesh& mesh, const fluidFractionModel& model, const dictionary& couplingProperties
)
:
    mesh_(mesh),
    model_(model),
    localBounds_(mesh.points(), false),
    insideMargin_(insideMargins(mesh)),
    verticalSharing_(false)
{
    const word sharing(couplingProperties.getOrDefault<word>("verticalSharing", "none"));
    if (sharing != "none" && sharing != "linear")
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'verticalSharing' is '" << sharing << "': none or linear"
            << exit(FatalIOError);
    }
    verticalSharing_ = sharing == "linear";
    if (verticalSharing_)
    {
        above_.setSize(mesh.nCells(), -1);
        below_.setSize(mesh.nCells(), -1);
        aboveFaceZ_.setSize(mesh.nCells(), 0);
        belowFaceZ_.setSize(mesh.nCells(), 0);
        const vectorField& Sf = mesh.faceAreas();
        const vectorField& C = mesh.cellCentres();
        for (label facei = 0; facei < mesh.nInternalFaces(); ++facei)
        {
            if (mag(Sf[facei].z()) < 0.99*mag(Sf[facei]))
            {
                continue;
            }
            const label own = mesh.faceOwner()[facei], nei = mesh.faceNeighbour()[facei];
            const bool ownBelow = C[own].z() < C[nei].z();
            (ownBelow ? above_[own] : below_[own]) = nei;
            (ownBelow ? below_[nei] : above_[nei]) = own;
            const scalar zf = mesh.faceCentres()[facei].z();
            (ownBelow ? aboveFaceZ_[own] : belowFaceZ_[own]) = zf;
            (ownBelow ? belowFaceZ_[nei] : aboveFaceZ_[nei]) = zf;
        }
    }

    // Built on demand with parallel communication: build them here, on every
    // rank, since only ranks with particles nearby would ask for them later.
    mesh_.tetBasePtIs();
    mesh_.cellTree();
    mesh_.cellPoints();
    mesh_.pointCells();
}


scalarField particleLocator::insideMargins(const fvMesh& mesh)
{
    // A point farther inside every face plane of a cell than its faces' warp
    // is inside the cell's tet decomposition, so the cheap face-plane test
    // finds the cell the tet test would; a point nearer a face (on it, or by
    // a warped face) is left to the tet test, so no cell assignment changes.
    // The round-off allowance is relative to the cell's size.
    scalarField margin(mesh.nCells(), 0);
    const pointField& points = mesh.points();
    forAll(margin, celli)
    {
        scalar warp = 0;
        for (const label facei : mesh.cells()[celli])
        {
            const vector n = mesh.faceAreas()[facei]/mag(mesh.faceAreas()[facei]);
            for (const label pointi : mesh.faces()[facei])
            {
                warp = max(warp, mag((points[pointi] - mesh.faceCentres()[facei]) & n));
            }
        }
        margin[celli] = warp + 1e-6*cbrt(mesh.cellVolumes()[celli]);
    }
    return margin;
}


label particleLocator::findCell(const point& p, label hint) const
{
    if (hint >= 0 && mesh_.pointInCell(p, hint, polyMesh::CELL_TETS))
    {
        return hint;
    }
    return mesh_.findCell(p, polyMesh::CELL_TETS);
}


scalar particleLocator::clearance(const point& p, label cell) const
{
    // The mesh's accessors are virtual: taken once, not per face.
    const labelList& owner = mesh_.faceOwner();
    const vectorField& areas = mesh_.faceAreas();
    const vectorField& centres = mesh_.faceCentres();
    scalar nearest = GREAT;
    for (const label facei : mesh_.cells()[cell])
    {
        // Face normals point out of their owner.
        const vector outward = (owner[facei] == cell ? 1 : -1)*areas[facei]/mag(areas[facei]);
        nearest = min(nearest, (centres[facei] - p) & outward);
    }
    return nearest;
}


bool particleLocator::insideBy(const point& p, label cell, scalar margin) const
{
    // Leaves at the first face that says no (most cells tried are not the
    // point's). With margin 0 this is primitiveMesh::pointInCell's test to the
    // bit: (centre - p) & area is -(area & (p - centre)) exactly.
    const labelList& owner = mesh_.faceOwner();
    const vectorField& areas = mesh_.faceAreas();
    const vectorField& centres = mesh_.faceCentres();
    for (const label facei : mesh_.cells()[cell])
    {
        const vector& area = areas[facei];
        const scalar inward = (centres[facei] - p) & area;
        if ((owner[facei] == cell ? inward : -inward) < (margin > 0 ? margin*mag(area) : 0))
        {
            return false;
        }
    }
    return true;
}


label particleLocator::sampleCell(const point& p, label centreCell) const
{
    if (centreCell >= 0)
    {
        if (insideBy(p, centreCell, 0))
        {
            return centreCell;
        }
        for (const label neighbour : mesh_.cellCells()[centreCell])
        {
            if (insideBy(p, neighbour, 0))
            {
                return neighbour;
            }
        }
        // Across an edge or a corner of the centre cell: a cell sharing one
        // of its points, where the point is well inside it (insideMargins);
        // nearer a face the full search decides, as it always did.
        for (const label pointi : mesh_.cellPoints()[centreCell])
        {
            for (const label celli : mesh_.pointCells()[pointi])
            {
                if (celli != centreCell && insideBy(p, celli, insideMargin_[celli]))
                {
                    return celli;
                }
            }
        }
    }
    // Samples of spheres at a wall or crossing the water surface lie outside
    // the mesh: no cell has them, and the search would look through them all.
    if (!localBounds_.contains(p))
    {
        return -1;
    }
    return mesh_.findCell(p, polyMesh::CELL_TETS);
}


void particleLocator::addSample(label particle, label cell, scalar z, scalar share)
{
    if (verticalSharing_)
    {
        // The sample's volume as a slab as high as the lower of the two cells,
        // centred on it: the share in the neighbour is the slab's part beyond
        // the face, 1/2 at the face from either side. Equal cells: linear in z
        // between their centres. Unequal cells (a graded mesh): a thin cell
        // never takes volume from deeper in its thick neighbour than its own
        // half height (linear between centres filled 4 cm cells beside 0.18 m
        // ones past their volume: coupling/README.md, vof level).
        const scalar zc = mesh_.cellCentres()[cell].z();
        const bool up = z >= zc;
        const label neighbour = up ? above_[cell] : below_[cell];
        if (neighbour >= 0)
        {
            const scalar zf = up ? aboveFaceZ_[cell] : belowFaceZ_[cell];
            const scalar slab = 2*min(mag(zf - zc), mag(mesh_.cellCentres()[neighbour].z() - zf));
            const scalar w = max(scalar(0), scalar(0.5) - mag(zf - z)/slab);
            samples_.append(particleSample{particle, cell, (1 - w)*share});
            samples_.append(particleSample{particle, neighbour, w*share});
            return;
        }
    }
    samples_.append(particleSample{particle, cell, share});
}


boundBox particleLocator::particleRegion(scalar openAbove) const
{
    boundBox region(localBounds_);
    // The mesh's top is at the surface to 1e-6 m (checked by the solvers).
    if (openAbove < GREAT && region.max().z() >= openAbove - 1e-6)
    {
        region.max().z() = GREAT;
    }
    return region;
}


void particleLocator::locate(const std::vector<::iceCoupling::CouplingParticle>& particles)
{
    const label nParticles = particles.size();
    const vectorList& offsets = model_.unitOffsets();
    const scalarList& shares = model_.shares();
    const label nSamples = offsets.size();
    const int myRank = Pstream::myProcNo();
    const int nobody = Pstream::nProcs();

    // The cell each particle's centre was in at the last call, as the search's
    // first guess: matched by tag, since a rank's list changes as particles
    // come near its part of the mesh and leave it (both lists are sorted by tag).
    labelList previous(nParticles, -1);
    for (std::size_t i = 0, j = 0; i < particles.size() && j < centreTags_.size();)
    {
        if (particles[i].tag < centreTags_[j])
        {
            ++i;
        }
        else if (centreTags_[j] < particles[i].tag)
        {
            ++j;
        }
        else
        {
            previous[i++] = centreCell_[j++];
        }
    }
    centreCell_.setSize(nParticles);
    centreCell_ = -1;
    centreTags_.resize(nParticles);
    for (label i = 0; i < nParticles; ++i)
    {
        centreTags_[i] = particles[i].tag;
    }
    labelList cellOfSample(nParticles*nSamples, -1);
    exchange_ = particleRowExchange(particles);

    // One list for one reduction: the centre owner then the sample owners of each particle.
    std::vector<int> owner(nParticles*(nSamples + 1), nobody);
    for (label i = 0; i < nParticles; ++i)
    {
        const point c(particles[i].position[0], particles[i].position[1], particles[i].position[2]);
        const scalar d = particles[i].diameter;
        if (!localBounds_.overlaps(c, sqr(0.5*d)))
        {
            continue;
        }
        // Most centres are still well inside last call's cell: the face
        // planes decide it, without the tet test.
        label cell = -1;
        scalar centreClearance = -GREAT;
        if (previous[i] >= 0)
        {
            centreClearance = clearance(c, previous[i]);
            if (centreClearance > insideMargin_[previous[i]])
            {
                cell = previous[i];
            }
        }
        if (cell < 0)
        {
            cell = findCell(c, previous[i]);
            if (cell != previous[i])   // the same cell's clearance is known
            {
                centreClearance = cell >= 0 ? clearance(c, cell) : -GREAT;
            }
        }
        if (cell >= 0)
        {
            centreCell_[i] = cell;
            owner[i*(nSamples + 1)] = myRank;
        }
        // Most particles lie wholly inside their cell: no sample search.
        const bool inside = cell >= 0 && centreClearance >= 0.5*d;
        for (label s = 0; s < nSamples; ++s)
        {
            const label sc = inside ? cell : sampleCell(c + d*offsets[s], cell);
            if (sc >= 0)
            {
                cellOfSample[i*nSamples + s] = sc;
                owner[i*(nSamples + 1) + 1 + s] = myRank;
            }
        }
    }
    exchange_.min(owner, nSamples + 1);

    samples_.clear();
    for (label i = 0; i < nParticles; ++i)
    {
        const int* o = &owner[i*(nSamples + 1)];
        if (o[0] == nobody)
        {
            const auto& p = particles[i];
            FatalErrorInFunction
                << "particle " << p.tag << " at (" << p.position[0] << ' ' << p.position[1]
                << ' ' << p.position[2] << ") is outside the fluid mesh (bounds "
                << mesh_.bounds() << "): with hydrodynamics"
                << " level cfd every particle must stay inside the mesh; enlarge the mesh"
                << " (system/blockMeshDict) or keep the particles in it with walls in the DEM script"
                << exit(FatalError);
        }
        if (o[0] != myRank)
        {
            centreCell_[i] = -1;
        }
        for (label s = 0; s < nSamples; ++s)
        {
            const scalar z = particles[i].position[2] + particles[i].diameter*offsets[s].z();
            if (o[1 + s] == myRank)
            {
                addSample(i, cellOfSample[i*nSamples + s], z, shares[s]);
            }
            else if (o[1 + s] == nobody && o[0] == myRank)
            {
                addSample(i, centreCell_[i], z, shares[s]);
            }
        }
    }
}

} // namespace iceCoupling
} // namespace Foam
