#include "ui/viewer/viewer_app.h"

#include "ui/viewer/session_script.h"
#include "ui/viewer/viewer.h"

namespace plumb::viewer {

int runViewer(const ViewerOptions& options) {
  // A bad script fails before any window opens.
  if (!options.script.empty()) readSessionScript(options.script);
  Viewer viewer(options);
  return viewer.run();
}

}  // namespace plumb::viewer
