# scalar   red green blue   opacity
units normalized          # optional
0.00   0 0 0   0
0.40   1 0.8 0.6   0.05
1.00   1 1 1   0.9
