// An itk::DataObject that carries a vtouch::QSkeleton through an ITK pipeline.
#pragma once

#include "vtouchQSkeleton.h"

#include <itkDataObject.h>
#include <itkObjectFactory.h>

namespace vtouch
{

class QSkeletonObject : public itk::DataObject
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(QSkeletonObject);

  using Self = QSkeletonObject;
  using Superclass = itk::DataObject;
  using Pointer = itk::SmartPointer<Self>;
  using ConstPointer = itk::SmartPointer<const Self>;

  itkNewMacro(Self);
  itkTypeMacro(QSkeletonObject, DataObject);

  QSkeleton& Get() { return this->m_Skeleton; }
  const QSkeleton& Get() const { return this->m_Skeleton; }

  void Initialize() override
  {
    Superclass::Initialize();
    this->m_Skeleton = QSkeleton{};
  }

  void Graft(const itk::DataObject* data) override
  {
    if (const auto* other = dynamic_cast<const Self*>(data))
    {
      this->m_Skeleton = other->m_Skeleton;
    }
  }

protected:
  QSkeletonObject() = default;
  ~QSkeletonObject() override = default;

  void PrintSelf(std::ostream& os, itk::Indent indent) const override
  {
    Superclass::PrintSelf(os, indent);
    os << indent << "Paths: " << this->m_Skeleton.paths.size() << "\n";
    os << indent << "Junctions: " << this->m_Skeleton.junctions.size() << "\n";
    os << indent << "Points: " << this->m_Skeleton.pointCount() << "\n";
  }

private:
  QSkeleton m_Skeleton;
};

} // namespace vtouch
