"""What `make hub` sets up on the host: the learners' environment, the proxy, the accounts."""
