// Loaded into the hub's proxy (node --import, course_lib/hub/provision/proxy.py: proxy_argv).
//
// configurable-http-proxy sends each request for a Unix-socket target (a learner's server
// behind the wall) on a connection of its own with "Connection: close". The server closes
// that socket as soon as it has answered, and a write of the proxy's still pending after the
// request's body then fails on the closed Unix socket (EPIPE): the proxy answers 503 for a
// request the server did carry out. Learners saw "Error Starting Kernel: 503" and failed
// saves, for a few in a hundred requests with a body. TCP targets do not fail so: the proxy
// keeps their connections alive. This gives Unix-socket targets the same kind of keep-alive
// agent; tests/hub/test_proxy_unix_targets.py sends requests with bodies through it.
import http from "node:http";
import { ConfigurableProxy } from "configurable-http-proxy";

const unixAgent = new http.Agent({ keepAlive: true });
const optionsForTarget = ConfigurableProxy.prototype.proxyOptsForTarget;

ConfigurableProxy.prototype.proxyOptsForTarget = function (target) {
  const options = optionsForTarget.call(this, target);
  if (options.target.socketPath && !options.agent) {
    options.agent = unixAgent;
  }
  return options;
};
