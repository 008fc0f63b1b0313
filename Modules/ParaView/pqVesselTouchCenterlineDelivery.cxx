#include "pqVesselTouchCenterlineDelivery.h"

#include "pqServer.h"

#include "vtkClientServerStream.h"
#include "vtkDataObjectTypes.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkType.h"

namespace
{
vtkSmartPointer<vtkSMSourceProxy> newFilter(pqServer* server, const char* name)
{
  vtkSmartPointer<vtkSMSourceProxy> proxy;
  proxy.TakeReference(
    vtkSMSourceProxy::SafeDownCast(server->proxyManager()->NewProxy("filters", name)));
  return proxy;
}
} // namespace

bool pqVesselTouchCenterlineDelivery::isRemote(pqServer* server)
{
  return server && server->isRemote();
}

vtkSMProxy* pqVesselTouchCenterlineDelivery::deliver(pqServer* server,
  vtkSMProxy* centerline,
  unsigned int& port)
{
  if (!centerline || !isRemote(server))
  {
    this->clear();
    return centerline;
  }
  if (!this->Reducer || !this->Mover)
  {
    this->Reducer = newFilter(server, "ReductionFilter");
    this->Mover = newFilter(server, "ClientServerMoveData");
    if (!this->Reducer || !this->Mover)
    {
      this->clear();
      return nullptr;
    }
    vtkSMPropertyHelper(this->Reducer, "PostGatherHelperName").Set("vtkAppendPolyData");
    vtkSMPropertyHelper(this->Mover, "Input").Set(this->Reducer, 0);
    vtkSMPropertyHelper(this->Mover, "OutputDataType").Set(VTK_POLY_DATA);
  }
  vtkSMPropertyHelper(this->Reducer, "Input").Set(centerline, port);
  this->Reducer->UpdateVTKObjects();
  this->Mover->UpdateVTKObjects();
  this->update();
  port = 0;
  return this->Mover;
}

void pqVesselTouchCenterlineDelivery::update()
{
  if (this->Reducer && this->Mover)
  {
    this->Reducer->UpdatePipeline();
    // Both halves of the mover execute, or neither: the server's half re-executes when the
    // centerline changed and sends it, but the client's half has no input here and would think
    // itself up to date, leave the data in the session's socket and break the session at its
    // next message ("Wrong tag", ParaView aborts; seen under Xvfb on a second Extract).
    vtkClientServerStream stream;
    stream << vtkClientServerStream::Invoke << VTKOBJECT(this->Mover) << "Modified"
           << vtkClientServerStream::End;
    this->Mover->GetSession()->ExecuteStream(this->Mover->GetLocation(), stream);
    this->Mover->UpdatePipeline();
  }
}

void pqVesselTouchCenterlineDelivery::clear()
{
  this->Mover = nullptr;
  this->Reducer = nullptr;
}
