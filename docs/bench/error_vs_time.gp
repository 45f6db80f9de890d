set terminal pngcairo size 1600,1520 font 'sans,9'
set output 'docs/bench/error_vs_time.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key bottom left
set multiplot layout 4,4 title 'relative RMSE of pixel irradiance against wall time (trace + resolve)'
set title 'point_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_0 << EOD
0.0014153 2.45367
0.00180762 0.800998
0.00519195 0.252205
0.038427 0.0789241
0.452794 0.0249586
3.14231 0.0080504
EOD
$d1_0 << EOD
0.000237512 2.45367
0.000779927 0.800998
0.00644809 0.252205
0.0501522 0.0789241
0.496773 0.0249586
4.95161 0.0080504
EOD
plot $d0_0 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_0 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0080504*(x/3.14231)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'point_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_1 << EOD
0.00263459 3.92447
0.00342302 1.32748
0.00932945 0.424239
0.0345925 0.125531
0.407565 0.0389811
3.60513 0.0125417
EOD
$d1_1 << EOD
0.000300466 3.92447
0.000834478 1.32748
0.00551136 0.424239
0.0485646 0.125531
0.512202 0.0389811
4.89832 0.0125417
EOD
plot $d0_1 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_1 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.0125417*(x/3.60513)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_on_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_2 << EOD
0.00190908 1.50901
0.00189005 0.473034
0.00706644 0.145537
0.0705923 0.0485828
0.554368 0.0153916
4.06485 0.00474422
EOD
$d1_2 << EOD
0.000240126 1.50901
0.00101653 0.473034
0.00758912 0.145537
0.0629001 0.0485828
0.621318 0.0153916
6.63744 0.00474422
EOD
plot $d0_2 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_2 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00474422*(x/4.06485)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'disk_off_axis' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_3 << EOD
0.000981938 2.01884
0.00134804 0.618676
0.00443158 0.192406
0.0391923 0.0605442
0.468495 0.0184
4.18292 0.00625028
EOD
$d1_3 << EOD
0.000205555 2.01884
0.00114391 0.618676
0.00936436 0.192406
0.0681813 0.0605442
0.721306 0.0184
11.9655 0.00625028
EOD
plot $d0_3 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_3 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00625028*(x/4.18292)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'furnace' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_4 << EOD
0.000888448 1.95744
0.000890802 0.691132
0.00400473 0.234013
0.035757 0.0714504
0.399344 0.0203218
3.17565 0.00700781
EOD
$d1_4 << EOD
0.000152577 1.95744
0.00086215 0.691132
0.0102847 0.234013
0.1117 0.0714504
1.13773 0.0203218
10.1123 0.0070078
EOD
plot $d0_4 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_4 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00700781*(x/3.17565)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_d65' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_5 << EOD
0.000811123 0.663477
0.00124393 0.205715
0.00627891 0.0652183
0.0698572 0.0189764
0.473142 0.00626652
4.73786 0.00201212
EOD
$d1_5 << EOD
0.000144915 0.663477
0.000873496 0.205715
0.00626518 0.0652183
0.0546542 0.0189764
0.556873 0.00626653
5.71196 0.00201212
EOD
plot $d0_5 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_5 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.73786)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_a' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_6 << EOD
0.00105965 0.663477
0.00182942 0.205715
0.0118515 0.0652183
0.0625815 0.0189764
0.578451 0.00626653
5.17795 0.00201212
EOD
$d1_6 << EOD
0.000136703 0.663477
0.000771225 0.205715
0.00624793 0.0652183
0.0618734 0.0189764
0.558592 0.00626652
5.64041 0.00201212
EOD
plot $d0_6 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_6 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/5.17795)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f2' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_7 << EOD
0.000766718 0.663477
0.00124788 0.205715
0.0061127 0.0652183
0.049143 0.0189764
0.516899 0.00626652
4.57388 0.00201212
EOD
$d1_7 << EOD
0.000182621 0.663477
0.00107301 0.205715
0.0076059 0.0652183
0.0593741 0.0189764
0.576333 0.00626653
5.95953 0.00201212
EOD
plot $d0_7 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_7 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.57388)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_f11' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_8 << EOD
0.000910411 0.663477
0.00211334 0.205715
0.00516836 0.0652183
0.0474521 0.0189764
0.483408 0.00626652
4.23341 0.00201212
EOD
$d1_8 << EOD
0.00016144 0.663477
0.00095704 0.205715
0.00716487 0.0652183
0.0605793 0.0189764
0.603396 0.00626653
5.73862 0.00201212
EOD
plot $d0_8 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_8 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/4.23341)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'uniform_led_b3' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_9 << EOD
0.000378862 0.663477
0.00072829 0.205715
0.00351882 0.0652183
0.0322634 0.0189764
0.450225 0.00626652
3.79363 0.00201212
EOD
$d1_9 << EOD
0.000192225 0.663477
0.00108394 0.205715
0.00742034 0.0652183
0.060251 0.0189764
0.587386 0.00626653
5.48188 0.00201212
EOD
plot $d0_9 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_9 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00201212*(x/3.79363)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'laser_532' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_10 << EOD
0.00115819 0.745339
0.00127332 0.237721
0.00499432 0.0773089
0.0410731 0.0238119
0.496295 0.00742963
3.37315 0.00228176
EOD
$d1_10 << EOD
0.000201329 0.745339
0.000750734 0.237721
0.00675469 0.0773089
0.0547484 0.0238119
0.554242 0.00742963
5.50372 0.00228175
EOD
plot $d0_10 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_10 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00228176*(x/3.37315)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_rect' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_11 << EOD
0.00211184 0.651221
0.00196545 0.191512
0.00884313 0.0673776
0.0654109 0.0199254
0.660203 0.00640466
4.8084 0.00224578
EOD
$d1_11 << EOD
0.000270411 0.651221
0.00114219 0.191512
0.00858183 0.0673777
0.0808493 0.0199254
0.782928 0.00640467
7.87182 0.00224578
EOD
plot $d0_11 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_11 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00224578*(x/4.8084)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
set title 'pinhole_small' noenhanced
set xlabel 'seconds'
set ylabel 'relative RMSE'
$d0_12 << EOD
0.00123143 0.878509
0.00240672 0.265263
0.00729874 0.0888789
0.0553333 0.0285845
0.509157 0.00867623
4.42805 0.00283295
EOD
$d1_12 << EOD
0.000239766 0.878509
0.00142259 0.265263
0.0091472 0.0888789
0.0721868 0.0285845
0.715567 0.00867623
7.24803 0.00283295
EOD
plot $d0_12 with linespoints lw 2 title 'llvmpipe (LLVM 15.0.6, 256 bits)' noenhanced, $d1_12 with linespoints lw 2 title 'CPU reference, 2 threads' noenhanced, 0.00283295*(x/4.42805)**-0.5 with lines dt 2 lc 'gray' title 'N^{-1/2}'
unset multiplot
