"""What the Python, C and Promela targets share about state machines: the packets
they exchange and the lowering of their actions."""
