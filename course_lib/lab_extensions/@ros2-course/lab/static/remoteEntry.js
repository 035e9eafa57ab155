// The ROS 2 course's JupyterLab plugin, written by hand (no build step): a module-federation
// container as JupyterLab loads prebuilt extensions (window._JUPYTERLAB[name] with init/get).
//
// Why: Run > Run All Cells on a notebook whose kernel was shut down runs every cell at once.
// The first cell starts a kernel; the others, seeing a kernel name pending, go straight on to
// execute, find no kernel yet and are skipped: only the first cell runs. Here, while a
// session's kernel is starting, the session says it has no kernel, so every other cell asks to
// start one too, and that start is single-flight: each cell waits for the one kernel, then all
// run, in order.
(function () {
  "use strict";
  var NAME = "@ros2-course/lab";

  function startOnce(context) {
    var proto = Object.getPrototypeOf(context);
    if (!proto || typeof proto.startKernel !== "function" || proto.__ros2CourseStartOnce) {
      return;
    }
    var start = proto.startKernel;
    var noKernel = Object.getOwnPropertyDescriptor(proto, "hasNoKernel");
    if (!noKernel || typeof noKernel.get !== "function") {
      return;
    }
    Object.defineProperty(proto, "hasNoKernel", {
      configurable: true,
      get: function () {
        var starting = Boolean(this.__ros2CourseStarting);
        var kernel = this.session && this.session.kernel;
        return noKernel.get.call(this) || (starting && !kernel);
      },
    });
    proto.startKernel = function () {
      var self = this;
      if (!self.__ros2CourseStarting) {
        self.__ros2CourseStarting = Promise.resolve(start.call(self)).finally(function () {
          self.__ros2CourseStarting = null;
        });
      }
      return self.__ros2CourseStarting;
    };
    proto.__ros2CourseStartOnce = true;
  }

  function watch(app) {
    var patch = function () {
      var widget = app.shell.currentWidget;
      if (widget && widget.sessionContext) {
        startOnce(widget.sessionContext);
      }
    };
    patch();
    if (app.shell.currentChanged) {
      app.shell.currentChanged.connect(patch);
    }
  }

  var plugin = {
    id: NAME + ":start-kernel-once",
    description: "Run All on a notebook without a kernel starts one kernel, then every cell.",
    autoStart: true,
    activate: function (app) {
      watch(app);
    },
  };

  window._JUPYTERLAB = window._JUPYTERLAB || {};
  window._JUPYTERLAB[NAME] = {
    init: function () {},
    get: function (module) {
      if (module !== "./extension") {
        return Promise.reject(new Error(NAME + " has no module " + module));
      }
      return Promise.resolve(function () {
        return { __esModule: true, default: [plugin] };
      });
    },
  };
})();
