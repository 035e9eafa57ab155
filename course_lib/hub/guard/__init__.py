"""What keeps the hub's accounts apart and the hub itself whole: each lab's own network, processes
tied to the hub, bounded removals, locks and routes no other account can take, and the
gate that counts each account's connections to the hub's ports."""
