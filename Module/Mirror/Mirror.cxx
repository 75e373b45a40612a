#include "Mirror.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace catar
{
MirrorDescription::MirrorDescription()
  : type(MirrorTypes().front().name)
  , parameters(MirrorTypes().front().defaults)
{
}

MirrorDescription::MirrorDescription(std::string t, std::vector<double> p)
  : type(std::move(t))
  , parameters(std::move(p))
{
}

void Mirror::ReflectNear(
  int n, const Vec3*, const Vec3*, Vec3* mirrorPoints, unsigned char* settled) const
{
  for (int i = 0; i < n; ++i)
  {
    settled[i] = 0;
    mirrorPoints[i].setZero();
  }
}

void Mirror::Intersect(
  int n, const Vec3* directions, Vec3* points, Vec3* normals, unsigned char* hits) const
{
  for (int i = 0; i < n; ++i)
  {
    hits[i] = this->Intersect(directions[i], points[i], normals[i]) ? 1 : 0;
  }
}

int MirrorType::ParameterCount() const
{
  int count = 0;
  for (const MirrorParameter& p : this->parameters)
  {
    count += p.count;
  }
  return count;
}

int MirrorType::ParameterOffset(const std::string& key) const
{
  int offset = 0;
  for (const MirrorParameter& p : this->parameters)
  {
    if (p.key == key)
    {
      return offset;
    }
    offset += p.count;
  }
  return -1;
}

const MirrorParameter* MirrorType::FindParameter(const std::string& key) const
{
  for (const MirrorParameter& p : this->parameters)
  {
    if (p.key == key)
    {
      return &p;
    }
  }
  return nullptr;
}

const MirrorType* FindMirrorType(const std::string& name)
{
  for (const MirrorType& t : MirrorTypes())
  {
    if (t.name == name)
    {
      return &t;
    }
  }
  return nullptr;
}

const MirrorType* FindMirrorType(const std::string& name, std::size_t count)
{
  for (const MirrorType& t : MirrorTypes())
  {
    if (t.name == name && static_cast<std::size_t>(t.ParameterCount()) == count)
    {
      return &t;
    }
  }
  return nullptr;
}

std::string MirrorTypeNames()
{
  std::string names;
  for (const MirrorType& t : MirrorTypes())
  {
    if (FindMirrorType(t.name) == &t) // each name once
    {
      names += (names.empty() ? "" : ", ") + t.name;
    }
  }
  return names;
}

std::string ValidateMirror(const MirrorDescription& description)
{
  const MirrorType* type = FindMirrorType(description.type);
  std::ostringstream err;
  if (!type)
  {
    err << "unknown mirror type '" << description.type << "' (known: " << MirrorTypeNames() << ")";
    return err.str();
  }
  if (const MirrorType* variant = FindMirrorType(description.type, description.parameters.size()))
  {
    type = variant;
  }
  else
  {
    err << "a " << type->name << " mirror takes " << type->ParameterCount() << " numbers, not "
        << description.parameters.size();
    return err.str();
  }
  for (double v : description.parameters)
  {
    if (!std::isfinite(v))
    {
      return "mirror contains NaN or Inf";
    }
  }
  return type->validate ? type->validate(description) : std::string();
}

bool MirrorQuadric(const MirrorDescription& description, Mat3& A, Vec3& B, double& C)
{
  const MirrorType* type = FindMirrorType(description.type, description.parameters.size());
  return type && type->quadric &&
    static_cast<int>(description.parameters.size()) == type->ParameterCount() &&
    type->quadric(description, A, B, C);
}

std::shared_ptr<const Mirror> MakeMirror(const MirrorDescription& description, std::string& error)
{
  error = ValidateMirror(description);
  if (!error.empty())
  {
    return nullptr;
  }
  return FindMirrorType(description.type, description.parameters.size())->make(description);
}
} // namespace catar
