// The independent reference of noise_test.cpp: java.util.Random itself (the generator Processing fills its noise table
// with), a Java port of PApplet's noise() in Java's own float arithmetic, and Ken Perlin's ImprovedNoise (2002) as his
// reference page gives it. Run: javac ProcessingNoiseReference.java && java ProcessingNoiseReference (JDK 11 or later);
// the test copies its output.
import java.util.Random;

public class ProcessingNoiseReference {
  static final float PI = (float) Math.PI;
  static final float DEG_TO_RAD = PI / 180.0f;
  static final float SINCOS_PRECISION = 0.5f;
  static final int SINCOS_LENGTH = (int) (360f / SINCOS_PRECISION);
  static float[] cosLUT = new float[SINCOS_LENGTH];
  static {
    for (int i = 0; i < SINCOS_LENGTH; i++) cosLUT[i] = (float) Math.cos(i * DEG_TO_RAD * SINCOS_PRECISION);
  }
  static final int YWRAPB = 4, YWRAP = 1 << YWRAPB, ZWRAPB = 8, ZWRAP = 1 << ZWRAPB, SIZE = 4095;
  static int octaves = 4;
  static float falloff = 0.5f;
  static float[] perlin;
  static int TWOPI = SINCOS_LENGTH, HALF = SINCOS_LENGTH / 2;

  static void seed(long s) {
    Random r = new Random(s);
    perlin = new float[SIZE + 1];
    for (int i = 0; i < SIZE + 1; i++) perlin[i] = r.nextFloat();
  }

  static float fsc(float i) { return 0.5f * (1.0f - cosLUT[(int) (i * HALF) % TWOPI]); }

  static float noise(float x, float y, float z) {
    if (x < 0) x = -x;
    if (y < 0) y = -y;
    if (z < 0) z = -z;
    int xi = (int) x, yi = (int) y, zi = (int) z;
    float xf = x - xi, yf = y - yi, zf = z - zi;
    float r = 0, ampl = 0.5f;
    for (int i = 0; i < octaves; i++) {
      int of = xi + (yi << YWRAPB) + (zi << ZWRAPB);
      float rxf = fsc(xf), ryf = fsc(yf);
      float n1 = perlin[of & SIZE];
      n1 += rxf * (perlin[(of + 1) & SIZE] - n1);
      float n2 = perlin[(of + YWRAP) & SIZE];
      n2 += rxf * (perlin[(of + YWRAP + 1) & SIZE] - n2);
      n1 += ryf * (n2 - n1);
      of += ZWRAP;
      n2 = perlin[of & SIZE];
      n2 += rxf * (perlin[(of + 1) & SIZE] - n2);
      float n3 = perlin[(of + YWRAP) & SIZE];
      n3 += rxf * (perlin[(of + YWRAP + 1) & SIZE] - n3);
      n2 += ryf * (n3 - n2);
      n1 += fsc(zf) * (n2 - n1);
      r += n1 * ampl;
      ampl *= falloff;
      xi <<= 1; xf *= 2; yi <<= 1; yf *= 2; zi <<= 1; zf *= 2;
      if (xf >= 1.0f) { xi++; xf--; }
      if (yf >= 1.0f) { yi++; yf--; }
      if (zf >= 1.0f) { zi++; zf--; }
    }
    return r;
  }

  static final int[] P = new int[512];
  static {
    int[] permutation = {151,160,137,91,90,15,131,13,201,95,96,53,194,233,7,225,140,36,103,30,69,142,8,99,37,240,21,10,
      23,190,6,148,247,120,234,75,0,26,197,62,94,252,219,203,117,35,11,32,57,177,33,88,237,149,56,87,174,20,125,136,171,
      168,68,175,74,165,71,134,139,48,27,166,77,146,158,231,83,111,229,122,60,211,133,230,220,105,92,41,55,46,245,40,244,
      102,143,54,65,25,63,161,1,216,80,73,209,76,132,187,208,89,18,169,200,196,135,130,116,188,159,86,164,100,109,198,173,
      186,3,64,52,217,226,250,124,123,5,202,38,147,118,126,255,82,85,212,207,206,59,227,47,16,58,17,182,189,28,42,223,183,
      170,213,119,248,152,2,44,154,163,70,221,153,101,155,167,43,172,9,129,22,39,253,19,98,108,110,79,113,224,232,178,185,
      112,104,218,246,97,228,251,34,242,193,238,210,144,12,191,179,162,241,81,51,145,235,249,14,239,107,49,192,214,31,181,
      199,106,157,184,84,204,176,115,121,50,45,127,4,150,254,138,236,205,93,222,114,67,29,24,72,243,141,128,195,78,66,215,
      61,156,180};
    for (int i = 0; i < 256; i++) P[256 + i] = P[i] = permutation[i];
  }
  static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static double lerp(double t, double a, double b) { return a + t * (b - a); }
  static double grad(int hash, double x, double y, double z) {
    int h = hash & 15;
    double u = h < 8 ? x : y, v = h < 4 ? y : h == 12 || h == 14 ? x : z;
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
  }
  static double improved(double x, double y, double z) {
    int X = (int) Math.floor(x) & 255, Y = (int) Math.floor(y) & 255, Z = (int) Math.floor(z) & 255;
    x -= Math.floor(x); y -= Math.floor(y); z -= Math.floor(z);
    double u = fade(x), v = fade(y), w = fade(z);
    int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z, B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
    return lerp(w, lerp(v, lerp(u, grad(P[AA], x, y, z), grad(P[BA], x - 1, y, z)),
                           lerp(u, grad(P[AB], x, y - 1, z), grad(P[BB], x - 1, y - 1, z))),
                   lerp(v, lerp(u, grad(P[AA + 1], x, y, z - 1), grad(P[BA + 1], x - 1, y, z - 1)),
                           lerp(u, grad(P[AB + 1], x, y - 1, z - 1), grad(P[BB + 1], x - 1, y - 1, z - 1))));
  }

  public static void main(String[] args) {
    System.out.println("Random(0): " + new Random(0).nextInt() + " " + new Random(42).nextInt() + " " + new Random(-7).nextInt());
    Random r = new Random(12345);
    System.out.print("Random(12345).nextFloat x3:");
    for (int i = 0; i < 3; i++) System.out.print(" " + Float.floatToIntBits(r.nextFloat()));
    System.out.println();
    float[][] pts = {{0.1f, 0, 0}, {1.5f, 0, 0}, {3.7f, 2.2f, 0}, {-3.7f, 2.2f, 0}, {12.34f, 5.67f, 8.9f}, {100.01f, 0.5f, 0.25f}, {0.5f, 0.5f, 0.5f}};
    for (long s : new long[] {0, 42}) {
      seed(s);
      octaves = 4; falloff = 0.5f;
      for (float[] p : pts)
        System.out.println("seed " + s + " noise(" + p[0] + "f, " + p[1] + "f, " + p[2] + "f) bits " + Float.floatToIntBits(noise(p[0], p[1], p[2])) + " = " + noise(p[0], p[1], p[2]));
    }
    seed(42); octaves = 8; falloff = 0.65f;
    System.out.println("seed 42 detail(8, 0.65) noise(3.7f, 2.2f, 1.1f) bits " + Float.floatToIntBits(noise(3.7f, 2.2f, 1.1f)) + " = " + noise(3.7f, 2.2f, 1.1f));
    double[][] ip = {{3.14, 42, 7}, {0.5, 0.5, 0.5}, {-1.25, 2.75, 10.125}, {123.456, -78.9, 0.001}, {1, 2, 3}};
    for (double[] p : ip) System.out.println("improved(" + p[0] + ", " + p[1] + ", " + p[2] + ") = " + Double.doubleToLongBits(improved(p[0], p[1], p[2])) + " " + improved(p[0], p[1], p[2]));
  }
}
