"""A class on JupyterHub: the hub's set-up, the learners' servers and the progress service."""
