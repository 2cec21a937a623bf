units furlongs
0 0 0 0 0
