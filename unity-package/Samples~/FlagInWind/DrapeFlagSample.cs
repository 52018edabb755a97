using UnityEngine;

namespace Drape.Samples.Flag
{
    /// <summary>Drape sample "Flag in wind": add this to an empty GameObject in an empty scene and
    /// press Play. It builds a pole, a 2 m x 1.25 m flag pinned along the pole and a camera, and
    /// blows gusty wind across the flag (the wind changes every frame without allocating).</summary>
    [AddComponentMenu("Drape/Samples/Flag In Wind")]
    public sealed class DrapeFlagSample : MonoBehaviour
    {
        [Tooltip("Mean wind, m/s, in world space.")]
        public Vector3 MeanWind = new Vector3(6f, 0f, 1.5f);

        [Tooltip("Gust strength as a fraction of the mean wind.")]
        [Range(0f, 1f)] public float Gustiness = 0.5f;

        private DrapeCloth _flag;

        private void Start()
        {
            var pole = GameObject.CreatePrimitive(PrimitiveType.Cylinder);
            pole.name = "Pole";
            pole.transform.position = new Vector3(0f, 1.5f, 0f);
            pole.transform.localScale = new Vector3(0.05f, 1.5f, 0.05f);

            // Built inactive so every field is set before DrapeCloth.OnEnable creates the native cloth.
            var flag = new GameObject("Flag");
            flag.SetActive(false);
            flag.transform.position = new Vector3(0.03f, 2.9f, 0f); // top of the pole; the grid hangs down -Y and spans +X
            flag.AddComponent<MeshFilter>();
            flag.AddComponent<MeshRenderer>().sharedMaterial = pole.GetComponent<MeshRenderer>().sharedMaterial;
            _flag = flag.AddComponent<DrapeCloth>();
            _flag.Source = DrapeShapeSource.GeneratedGrid;
            _flag.Columns = 40;
            _flag.Rows = 25;
            _flag.Size = new Vector2(2f, 1.25f);
            _flag.PinMode = DrapePinMode.VertexList;
            for (int r = 0; r < _flag.Rows; ++r) _flag.AddPinnedVertex(r * _flag.Columns); // column 0: along the pole
            _flag.AirDrag = 1.5f;        // a flag is light and catches the wind
            _flag.TotalMass = 0.25f;
            _flag.SleepThreshold = 0f;   // never sleeps: the wind keeps it moving
            _flag.PauseWhenInvisible = false;
            _flag.Wind = MeanWind;
            // The generated grid is centred on X: shift it so its left edge (column 0) sits at the pole.
            flag.transform.position += new Vector3(0.5f * _flag.Size.x, 0f, 0f);
            flag.SetActive(true);

            SampleSetup.CameraAndLight(new Vector3(1.2f, 2.2f, -4.5f), new Vector3(1.0f, 2.2f, 0f));
        }

        private void Update()
        {
            if (_flag == null) return;
            float t = Time.time;
            float gust = 1f + Gustiness * (Mathf.PerlinNoise(t * 0.7f, 0.3f) * 2f - 1f);
            float swirl = Gustiness * (Mathf.PerlinNoise(0.1f, t * 0.5f) * 2f - 1f);
            _flag.Wind = MeanWind * gust + new Vector3(0f, swirl, swirl * 2f);
            _flag.MarkParamsDirty(); // pushed to the native side before the next step
        }
    }
}
