#include "vtkCatadioptricImageSupport.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

void vtkCatadioptricImageSupport::RequestWholeExtents(
  vtkInformationVector** inputVector, std::initializer_list<int> ports)
{
  for (int port : ports)
  {
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
    {
      vtkInformation* info = inputVector[port]->GetInformationObject(i);
      if (info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        int extent[6];
        info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
        info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
    }
  }
}

void vtkCatadioptricImageSupport::CopyFrame(
  const unsigned char* in, int nc, vtkIdType n, unsigned char* out)
{
  vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      const unsigned char* s = in + nc * i;
      unsigned char* d = out + 4 * i;
      if (nc >= 3)
      {
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        d[3] = nc == 4 ? s[3] : 255;
      }
      else
      {
        d[0] = d[1] = d[2] = s[0];
        d[3] = nc == 2 ? s[1] : 255;
      }
    }
  });
}

void vtkCatadioptricImageSupport::FillColor(const double rgba[4], vtkIdType n, unsigned char* out)
{
  unsigned char bg[4];
  for (int k = 0; k < 4; ++k)
  {
    bg[k] = static_cast<unsigned char>(std::lround(255.0 * std::min(1.0, std::max(0.0, rgba[k]))));
  }
  vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      std::copy(bg, bg + 4, out + 4 * i);
    }
  });
}

bool vtkCatadioptricImageSupport::ReadTextures(vtkInformationVector* textures, bool repeat,
  std::vector<catar::TextureView>& views, std::string& error)
{
  views.clear();
  for (int t = 0; t < textures->GetNumberOfInformationObjects(); ++t)
  {
    vtkImageData* tex = vtkImageData::GetData(textures, t);
    vtkDataArray* texels = tex ? tex->GetPointData()->GetScalars() : nullptr;
    int dims[3] = { 0, 0, 0 };
    if (tex)
    {
      tex->GetDimensions(dims);
    }
    const int nc = texels ? texels->GetNumberOfComponents() : 0;
    if (!texels || texels->GetDataType() != VTK_UNSIGNED_CHAR || dims[2] != 1 || dims[0] < 1 ||
      dims[1] < 1 || !(nc == 1 || nc == 3 || nc == 4))
    {
      error = "Texture " + std::to_string(t) +
        " must be a 2D unsigned char image with 1, 3 or 4 components.";
      views.clear();
      return false;
    }
    catar::TextureView view;
    view.data = static_cast<const std::uint8_t*>(texels->GetVoidPointer(0));
    view.width = dims[0];
    view.height = dims[1];
    view.channels = nc;
    view.rowStride = static_cast<std::ptrdiff_t>(nc) * dims[0];
    view.repeat = repeat;
    views.push_back(view);
  }
  return true;
}

vtkDataArray* vtkCatadioptricImageSupport::TextureCoordinates(vtkPolyData* mesh)
{
  vtkDataArray* t = mesh->GetPointData()->GetTCoords();
  for (const char* name : { "TCoords", "TextureCoordinates" })
  {
    if (!t)
    {
      t = mesh->GetPointData()->GetArray(name);
    }
  }
  return (t && t->GetNumberOfComponents() >= 2) ? t : nullptr;
}
