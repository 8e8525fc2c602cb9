#include "PlanPolygon.H"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace iceDEM
{

namespace
{
double cross(const Vec2& a, const Vec2& b)
{
    return a.x()*b.y() - a.y()*b.x();
}
}


PlanPolygon::PlanPolygon(std::vector<Vec2> vertices)
:
    vertices_(std::move(vertices))
{
    if (vertices_.size() >= 3 && area() < 0.0)
    {
        throw std::invalid_argument("PlanPolygon: vertices must run counter-clockwise");
    }
}


PlanPolygon PlanPolygon::rectangle(double length, double width)
{
    if (!(length > 0.0 && width > 0.0))
    {
        throw std::invalid_argument("PlanPolygon::rectangle: length and width must be positive");
    }
    return PlanPolygon({{0, 0}, {length, 0}, {length, width}, {0, width}});
}


PlanPolygon PlanPolygon::regular(int n, double radius)
{
    std::vector<Vec2> v;
    for (int k = 0; k < n; ++k)
    {
        const double a = 2.0*M_PI*k/n;
        v.emplace_back(radius*std::cos(a), radius*std::sin(a));
    }
    return PlanPolygon(std::move(v));
}


double PlanPolygon::area() const
{
    double twice = 0.0;
    for (std::size_t k = 0; k < vertices_.size(); ++k)
    {
        twice += cross(vertices_[k], vertices_[(k + 1) % vertices_.size()]);
    }
    return 0.5*twice;
}


Vec2 PlanPolygon::centroid() const
{
    Vec2 sum = Vec2::Zero();
    double twice = 0.0;
    for (std::size_t k = 0; k < vertices_.size(); ++k)
    {
        const Vec2& a = vertices_[k];
        const Vec2& b = vertices_[(k + 1) % vertices_.size()];
        const double c = cross(a, b);
        sum += (a + b)*c;
        twice += c;
    }
    return sum/(3.0*twice);
}


bool PlanPolygon::contains(const Vec2& p) const
{
    const double tolerance = 1e-12;
    for (std::size_t k = 0; k < vertices_.size(); ++k)
    {
        const Vec2& a = vertices_[k];
        const Vec2& b = vertices_[(k + 1) % vertices_.size()];
        if (cross(b - a, p - a) < -tolerance*(b - a).norm())
        {
            return false;
        }
    }
    return !vertices_.empty();
}


PlanPolygon PlanPolygon::clipped(const Vec2& point, const Vec2& normal) const
{
    std::vector<Vec2> kept;
    const std::size_t n = vertices_.size();
    for (std::size_t k = 0; k < n; ++k)
    {
        const Vec2& a = vertices_[k];
        const Vec2& b = vertices_[(k + 1) % n];
        const double da = (a - point).dot(normal);
        const double db = (b - point).dot(normal);
        if (da <= 0.0)
        {
            kept.push_back(a);
        }
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0))
        {
            kept.push_back(a + (b - a)*(da/(da - db)));
        }
    }
    PlanPolygon result;
    result.vertices_ = std::move(kept);
    return result;
}


double PlanPolygon::extent(const Vec2& direction) const
{
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Vec2& v : vertices_)
    {
        const double s = v.dot(direction);
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
    return hi - lo;
}


double PlanPolygon::aspectRatio() const
{
    double bestArea = std::numeric_limits<double>::infinity();
    double ratio = 1.0;
    for (std::size_t k = 0; k < vertices_.size(); ++k)
    {
        const Vec2 edge = (vertices_[(k + 1) % vertices_.size()] - vertices_[k]).normalized();
        const Vec2 across(-edge.y(), edge.x());
        const double a = extent(edge);
        const double b = extent(across);
        if (a*b < bestArea)
        {
            bestArea = a*b;
            ratio = std::max(a, b)/std::min(a, b);
        }
    }
    return ratio;
}


PlanPolygon PlanPolygon::translated(const Vec2& shift) const
{
    PlanPolygon result(*this);
    for (Vec2& v : result.vertices_)
    {
        v += shift;
    }
    return result;
}


PlanPolygon PlanPolygon::rotated(double angle) const
{
    const double c = std::cos(angle), s = std::sin(angle);
    PlanPolygon result(*this);
    for (Vec2& v : result.vertices_)
    {
        v = Vec2(c*v.x() - s*v.y(), s*v.x() + c*v.y());
    }
    return result;
}

} // namespace iceDEM
